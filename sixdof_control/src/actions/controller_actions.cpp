#include "sixdof_control/controller_actions.h"

#include <control_msgs/JointTrajectoryControllerState.h>
#include <ros/console.h>

namespace sixdof_control {

using sixdof_core::GoalState;
using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryResult;

sixdof_core::TrajectoryGoal fromMsg(const control_msgs::FollowJointTrajectoryGoal& msg) {
  sixdof_core::TrajectoryGoal goal;
  goal.joint_names = msg.trajectory.joint_names;
  for (const trajectory_msgs::JointTrajectoryPoint& p : msg.trajectory.points) {
    goal.points.push_back({p.positions, p.velocities, p.accelerations, p.time_from_start.toSec()});
  }
  for (const control_msgs::JointTolerance& t : msg.path_tolerance) {
    goal.path_tolerance.push_back({t.name, t.position, t.velocity, t.acceleration});
  }
  for (const control_msgs::JointTolerance& t : msg.goal_tolerance) {
    goal.goal_tolerance.push_back({t.name, t.position, t.velocity, t.acceleration});
  }
  goal.goal_time_tolerance = msg.goal_time_tolerance.toSec();
  goal.start_time = msg.trajectory.header.stamp.toSec();
  return goal;
}

namespace {

// Ends an action goal as succeeded, canceled (PREEMPTED once active) or aborted (logged as a warning under `who`).
template <class Handle, class Result>
void endGoal(Handle& handle, GoalState state, const Result& result, const std::string& text, const std::string& who) {
  if (state == GoalState::kSucceeded) {
    handle.setSucceeded(result, text);
  } else if (state == GoalState::kCanceled) {
    handle.setCanceled(result, text);
  } else {
    ROS_WARN_STREAM("[" << who << "] goal aborted: " << text);
    handle.setAborted(result, text);
  }
}

}  // namespace

TrajectoryActionServer::TrajectoryActionServer(ros::NodeHandle nh, const TrajectoryControllerSetup& setup,
                                               ControllerHost& host)
    : name_(setup.config.name), joints_(setup.joints), host_(host), server_(nh, "follow_joint_trajectory", false) {
  if (setup.state_publish_rate > 0.0) {
    state_period_ = 1.0 / setup.state_publish_rate;
    state_pub_ = nh.advertise<control_msgs::JointTrajectoryControllerState>("state", 1);
  }
  query_state_ = nh.advertiseService("query_state", &TrajectoryActionServer::queryState, this);
  server_.registerGoalCallback([this](Server::GoalHandle gh) { goalCallback(gh); });
  server_.registerCancelCallback([this](Server::GoalHandle gh) {
    if (active_.is(gh)) host_.cancel(name_);
  });
  server_.start();
}

void TrajectoryActionServer::goalCallback(Server::GoalHandle gh) {
  const sixdof_core::TrajectoryGoal goal = fromMsg(*gh.getGoal());
  auto record = std::make_shared<Goal>(gh);
  TrajectoryResult check;
  if (const std::string mimic_error = joints_.checkMimics(goal); !mimic_error.empty()) {
    check = TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, mimic_error);
  } else {
    check = host_.setGoal(name_, goal, [this, record](const GoalOutcome& o) {
      if (active_.endNow(record, o)) finish(*record, o);
    });
  }
  if (!check.ok()) {
    control_msgs::FollowJointTrajectoryResult result;
    result.error_code = static_cast<int>(check.status);
    result.error_string = check.message;
    ROS_WARN_STREAM("[" << name_ << "] goal rejected: " << check.message);
    gh.setRejected(result, check.message);
    return;
  }
  active_.accept(record, [&](const GoalOutcome& o) { finish(*record, o); });
}

void TrajectoryActionServer::finish(Goal& goal, const GoalOutcome& outcome) {
  control_msgs::FollowJointTrajectoryResult result;
  result.error_code = static_cast<int>(outcome.result.status);
  result.error_string = outcome.result.message;
  endGoal(goal.handle, outcome.state, result, outcome.result.message, name_);
}

bool TrajectoryActionServer::queryState(control_msgs::QueryTrajectoryState::Request& request,
                                        control_msgs::QueryTrajectoryState::Response& response) {
  // As joint_trajectory_controller: a state that cannot be sampled is a failed call, with the reason logged.
  if (!host_.commands(name_)) {
    ROS_ERROR_STREAM("[" << name_ << "] query_state: " << name_
                         << " does not command its joints now (another controller, e.g. gripper_cmd, has them)");
    return false;
  }
  const std::optional<sixdof_core::TrajectorySample> sample = host_.sample(name_, request.time.toSec());
  if (!sample) {
    ROS_ERROR_STREAM("[" << name_ << "] query_state: " << name_ << " has no trajectory yet");
    return false;
  }
  response.name = joints_.joints();
  response.position = sample->position;
  response.velocity = sample->velocity;
  response.acceleration = sample->acceleration;
  return true;
}

void TrajectoryActionServer::publish(const ros::Time& stamp) {
  const std::optional<sixdof_core::TrajectoryUpdate> update = host_.lastUpdate(name_);
  if (!update || update->desired.position.empty()) return;
  const std::shared_ptr<Goal> active = active_.get();
  // The state topic runs while this controller commands its joints (not while another controller, e.g.
  // gripper_cmd, has them).
  const double now = stamp.toSec();
  const bool state_due =
      state_period_ > 0.0 && host_.commands(name_) && (now >= next_state_ || now < next_state_ - state_period_);
  if (!active && !state_due) return;
  // The action feedback and the state topic carry the same fields.
  control_msgs::FollowJointTrajectoryFeedback fb;
  fb.header.stamp = stamp;
  fb.joint_names = joints_.joints();
  fb.desired.positions = update->desired.position;
  fb.desired.velocities = update->desired.velocity;
  fb.desired.accelerations = update->desired.acceleration;
  fb.error.positions = update->error.position;
  fb.error.velocities = update->error.velocity;
  for (std::size_t i = 0; i < fb.joint_names.size(); ++i) {
    fb.actual.positions.push_back(fb.desired.positions[i] - fb.error.positions[i]);
    fb.actual.velocities.push_back(fb.desired.velocities[i] - fb.error.velocities[i]);
  }
  if (active) active->handle.publishFeedback(fb);
  if (state_due) {
    control_msgs::JointTrajectoryControllerState state;
    state.header = fb.header;
    state.joint_names = fb.joint_names;
    state.desired = fb.desired;
    state.actual = fb.actual;
    state.error = fb.error;
    state_pub_.publish(state);
    next_state_ = now + state_period_;
  }
}

GripperActionServer::GripperActionServer(ros::NodeHandle nh, const std::string& gripper, ControllerHost& host)
    : name_(gripper), host_(host), server_(nh, "gripper_cmd", false) {
  server_.registerGoalCallback([this](Server::GoalHandle gh) { goalCallback(gh); });
  server_.registerCancelCallback([this](Server::GoalHandle gh) {
    if (active_.is(gh)) host_.cancelGripper(name_);
  });
  server_.start();
}

control_msgs::GripperCommandResult GripperActionServer::makeResult(bool reached_goal, bool stalled) const {
  const GripperReading reading = host_.gripperReading(name_);
  control_msgs::GripperCommandResult result;
  result.position = reading.position;
  result.effort = reading.effort;
  result.reached_goal = reached_goal;
  result.stalled = stalled;
  return result;
}

void GripperActionServer::goalCallback(Server::GoalHandle gh) {
  const sixdof_core::GripperGoal goal{gh.getGoal()->command.position, gh.getGoal()->command.max_effort};
  auto record = std::make_shared<Goal>(gh);
  const sixdof_core::GripperResult check = host_.setGripperGoal(name_, goal, [this, record](const GripperOutcome& o) {
    if (active_.endNow(record, o)) finish(*record, o);
  });
  if (!check.ok()) {
    ROS_WARN_STREAM("[" << name_ << "/gripper_cmd] goal rejected: " << check.message);
    gh.setRejected(makeResult(false, false), check.message);
    return;
  }
  active_.accept(record, [&](const GripperOutcome& o) { finish(*record, o); });
}

void GripperActionServer::finish(Goal& goal, const GripperOutcome& outcome) {
  endGoal(goal.handle, outcome.state, makeResult(outcome.reached_goal, outcome.stalled), outcome.message,
          name_ + "/gripper_cmd");
}

void GripperActionServer::publish() {
  const std::shared_ptr<Goal> active = active_.get();
  if (!active) return;
  const GripperReading reading = host_.gripperReading(name_);
  control_msgs::GripperCommandFeedback fb;
  fb.position = reading.position;
  fb.effort = reading.effort;
  active->handle.publishFeedback(fb);
}

ControllerActions::ControllerActions(const ros::NodeHandle& nh, const ControllerSetup& setup, ControllerHost& host) {
  for (const TrajectoryControllerSetup& c : setup.trajectory) {
    trajectory_.push_back(std::make_unique<TrajectoryActionServer>(ros::NodeHandle(nh, c.config.name), c, host));
  }
  if (setup.gripper) {
    gripper_ =
        std::make_unique<GripperActionServer>(ros::NodeHandle(nh, setup.gripper->name), setup.gripper->name, host);
  }
}

void ControllerActions::publish(const ros::Time& stamp) {
  for (const auto& server : trajectory_) server->publish(stamp);
  if (gripper_) gripper_->publish();
}

}  // namespace sixdof_control
