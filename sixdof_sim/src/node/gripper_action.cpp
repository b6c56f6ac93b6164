#include "gripper_action.h"

#include <ros/console.h>

#include <stdexcept>

#include "action_goal.h"

namespace sixdof_sim {

GripperActionHandler::GripperActionHandler(ros::NodeHandle nh, GripperControllerConfig config, World& world,
                                           JointArbiter& arbiter, std::function<double()> clock)
    : controller_(std::move(config)),
      world_(world),
      arbiter_(arbiter),
      clock_(std::move(clock)),
      server_(nh, "gripper_cmd", false) {
  const int w = world_.jointIndex(controller_.config().joint);
  if (w < 0) {
    throw std::invalid_argument("gripper_cmd of '" + controller_.config().name + "': joint '" +
                                controller_.config().joint + "' is not in the robot");
  }
  index_ = static_cast<std::size_t>(w);
  if (!world_.joints()[index_].mimic_of.empty()) {
    throw std::invalid_argument("gripper_cmd of '" + controller_.config().name + "': joint '" +
                                controller_.config().joint + "' is a mimic joint; command its master '" +
                                world_.joints()[index_].mimic_of + "'");
  }
  server_.registerGoalCallback([this](Server::GoalHandle gh) { goalCallback(gh); });
  server_.registerCancelCallback([this](Server::GoalHandle gh) { cancelCallback(gh); });
  server_.start();
}

control_msgs::GripperCommandResult GripperActionHandler::makeResult(bool reached_goal, bool stalled) const {
  control_msgs::GripperCommandResult result;
  result.position = world_.jointPositions()[index_];
  result.effort = world_.jointEfforts()[index_];
  result.reached_goal = reached_goal;
  result.stalled = stalled;
  return result;
}

void GripperActionHandler::finishActive(bool succeeded, bool canceled, bool reached_goal, bool stalled,
                                        const std::string& text) {
  const std::string server = controller_.config().name + "/gripper_cmd";
  finishGoal(&active_, makeResult(reached_goal, stalled), succeeded, canceled, server, text);
}

void GripperActionHandler::goalCallback(Server::GoalHandle gh) {
  const GripperGoal goal{gh.getGoal()->command.position, gh.getGoal()->command.max_effort};
  const GripperResult check = controller_.validate(goal);
  if (!check.ok()) {
    ROS_WARN_STREAM("[" << controller_.config().name << "/gripper_cmd] goal rejected: " << check.message);
    gh.setRejected(makeResult(false, false), check.message);
    return;
  }
  arbiter_.claim(this, {controller_.config().joint});
  controller_.setGoal(goal, clock_());
  finishActive(false, true, false, false, "preempted by a new goal");
  gh.setAccepted();
  active_ = gh;
}

void GripperActionHandler::cancelCallback(Server::GoalHandle gh) {
  if (!active_ || !(*active_ == gh)) {
    return;
  }
  controller_.cancel(world_.jointPositions()[index_]);
  finishActive(false, true, false, false, "canceled");
}

void GripperActionHandler::release() {
  controller_.cancel(world_.jointPositions()[index_]);
  finishActive(false, true, false, false, "preempted by another controller's goal");
}

void GripperActionHandler::reset() {
  controller_.hold(world_.jointPositions()[index_]);
  finishActive(false, true, false, false, "canceled by a world reset");
}

void GripperActionHandler::update(double now) {
  if (!arbiter_.owns(this, controller_.config().joint)) {
    return;
  }
  const GripperUpdate u = controller_.update(now, world_.jointPositions()[index_]);
  const Result r = world_.setPositionTarget(controller_.config().joint, u.command_position, 0.0, u.command_max_effort);
  if (!r.ok()) {
    ROS_ERROR_STREAM_THROTTLE(1.0, "[" << controller_.config().name << "/gripper_cmd] " << r.message);
  }
  if (u.finished) {
    const std::string text = u.reached_goal ? "reached the goal"
                             : u.state == GoalState::kSucceeded
                                 ? "stalled (closed on an object): counts as success, allow_stalling is true"
                                 : "stalled before reaching the goal";
    finishActive(u.state == GoalState::kSucceeded, false, u.reached_goal, u.stalled, text);
  }
}

void GripperActionHandler::publishFeedback(const ros::Time&) {
  if (!active_) {
    return;
  }
  const control_msgs::GripperCommandResult r = makeResult(false, false);
  control_msgs::GripperCommandFeedback fb;
  fb.position = r.position;
  fb.effort = r.effort;
  active_->publishFeedback(fb);
}

}  // namespace sixdof_sim
