#include "trajectory_action.h"

#include <ros/console.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <control_msgs/JointTrajectoryControllerState.h>

#include "action_goal.h"
#include "conversions.h"

namespace sixdof_sim {

TrajectoryActionHandler::TrajectoryActionHandler(ros::NodeHandle nh, TrajectoryControllerConfig config,
                                                 World& world, JointArbiter& arbiter, std::function<double()> clock,
                                                 double state_publish_rate)
    : controller_(std::move(config)),
      world_(world),
      arbiter_(arbiter),
      clock_(std::move(clock)),
      server_(nh, "follow_joint_trajectory", false) {
  if (state_publish_rate > 0.0) {
    state_period_ = 1.0 / state_publish_rate;
    state_pub_ = nh.advertise<control_msgs::JointTrajectoryControllerState>("state", 1);
  }
  const std::vector<std::string>& joints = controller_.joints();
  for (const std::string& j : joints) {
    const int w = world_.jointIndex(j);
    if (w < 0) {
      throw std::invalid_argument("controller '" + controller_.config().name + "': joint '" + j +
                                  "' is not in the robot");
    }
    world_index_.push_back(w);
    const JointInfo& info = world_.joints()[static_cast<std::size_t>(w)];
    if (info.mimic_of.empty()) {
      commanded_.push_back(j);
      continue;
    }
    const auto master = std::find(joints.begin(), joints.end(), info.mimic_of);
    if (master == joints.end()) {
      throw std::invalid_argument("controller '" + controller_.config().name + "': joint '" + j + "' mimics '" +
                                  info.mimic_of + "', which the controller must then also contain");
    }
    mimics_.push_back({world_index_.size() - 1, static_cast<std::size_t>(master - joints.begin()),
                       info.mimic_multiplier, info.mimic_offset});
  }
  std::vector<double> q, v;
  readState(&q, &v);
  controller_.hold(q);
  arbiter_.claim(this, commanded_);
  query_state_ = nh.advertiseService("query_state", &TrajectoryActionHandler::queryState, this);
  server_.registerGoalCallback([this](Server::GoalHandle gh) { goalCallback(gh); });
  server_.registerCancelCallback([this](Server::GoalHandle gh) { cancelCallback(gh); });
  server_.start();
}

void TrajectoryActionHandler::readState(std::vector<double>* q, std::vector<double>* v) const {
  const std::vector<double> positions = world_.jointPositions();
  const std::vector<double> velocities = world_.jointVelocities();
  q->clear();
  v->clear();
  for (int w : world_index_) {
    q->push_back(positions[static_cast<std::size_t>(w)]);
    v->push_back(velocities[static_cast<std::size_t>(w)]);
  }
}

bool TrajectoryActionHandler::ownsAny() const {
  for (const std::string& j : commanded_) {
    if (arbiter_.owns(this, j)) {
      return true;
    }
  }
  return false;
}

std::string TrajectoryActionHandler::checkMimics(const TrajectoryGoal& goal) const {
  const std::vector<std::string>& joints = controller_.joints();
  for (const Mimic& m : mimics_) {
    const auto pos = [&](const std::string& name) {
      return static_cast<std::size_t>(std::find(goal.joint_names.begin(), goal.joint_names.end(), name) -
                                      goal.joint_names.begin());
    };
    const std::size_t ji = pos(joints[m.joint]);
    const std::size_t mi = pos(joints[m.master]);
    for (std::size_t p = 0; p < goal.points.size(); ++p) {
      const double expected = m.multiplier * goal.points[p].positions[mi] + m.offset;
      if (std::abs(goal.points[p].positions[ji] - expected) > 1e-6) {
        std::ostringstream s;
        s << "point " << p << ": joint '" << joints[m.joint] << "' mimics '" << joints[m.master] << "' and must be "
          << expected << ", got " << goal.points[p].positions[ji];
        return s.str();
      }
    }
  }
  return "";
}

void TrajectoryActionHandler::finishActive(int code, const std::string& message, bool succeeded, bool canceled) {
  control_msgs::FollowJointTrajectoryResult result;
  result.error_code = code;
  result.error_string = message;
  finishGoal(&active_, result, succeeded, canceled, controller_.config().name, message);
}

void TrajectoryActionHandler::goalCallback(Server::GoalHandle gh) {
  const double now = clock_();
  const TrajectoryGoal goal = fromMsg(*gh.getGoal());
  control_msgs::FollowJointTrajectoryResult result;
  TrajectoryResult check = controller_.validate(goal, now);
  if (check.ok()) {
    const std::string mimic_error = checkMimics(goal);
    if (!mimic_error.empty()) {
      check = {TrajectoryErrorCode::kInvalidGoal, mimic_error};
    }
  }
  if (check.ok() && !ownsAny()) {
    // Take the joints back from the other driver and start from where they are now.
    arbiter_.claim(this, commanded_);
    std::vector<double> q, v;
    readState(&q, &v);
    controller_.hold(q);
  }
  if (check.ok()) {
    check = controller_.setGoal(goal, now);
  }
  if (!check.ok()) {
    result.error_code = static_cast<int>(check.status);
    result.error_string = check.message;
    ROS_WARN_STREAM("[" << controller_.config().name << "] goal rejected: " << check.message);
    gh.setRejected(result, check.message);
    return;
  }
  finishActive(static_cast<int>(TrajectoryErrorCode::kSuccessful), "preempted by a new goal", false, true);
  gh.setAccepted();
  active_ = gh;
}

bool TrajectoryActionHandler::queryState(control_msgs::QueryTrajectoryState::Request& request,
                                         control_msgs::QueryTrajectoryState::Response& response) {
  // As joint_trajectory_controller: a state that cannot be sampled is a failed call, with the reason logged.
  const std::string& name = controller_.config().name;
  if (!ownsAny()) {
    ROS_ERROR_STREAM("[" << name << "] query_state: " << name
                         << " does not command its joints now (another driver, e.g. gripper_cmd, has them)");
    return false;
  }
  const std::optional<TrajectorySample> sample = controller_.sample(request.time.toSec());
  if (!sample) {
    ROS_ERROR_STREAM("[" << name << "] query_state: " << name << " has no trajectory yet");
    return false;
  }
  response.name = controller_.joints();
  response.position = sample->position;
  response.velocity = sample->velocity;
  response.acceleration = sample->acceleration;
  return true;
}

void TrajectoryActionHandler::cancelCallback(Server::GoalHandle gh) {
  if (!active_ || !(*active_ == gh)) {
    return;
  }
  std::vector<double> q, v;
  readState(&q, &v);
  controller_.cancel(q);
  finishActive(static_cast<int>(TrajectoryErrorCode::kSuccessful), "canceled", false, true);
}

void TrajectoryActionHandler::release() {
  std::vector<double> q, v;
  readState(&q, &v);
  controller_.cancel(q);
  finishActive(static_cast<int>(TrajectoryErrorCode::kSuccessful), "preempted by another controller's goal", false,
               true);
}

void TrajectoryActionHandler::reset() {
  std::vector<double> q, v;
  readState(&q, &v);
  controller_.hold(q);
  finishActive(static_cast<int>(TrajectoryErrorCode::kSuccessful), "canceled by a world reset", false, true);
}

void TrajectoryActionHandler::update(double now) {
  if (!ownsAny()) {
    return;
  }
  std::vector<double> q, v;
  readState(&q, &v);
  last_update_ = controller_.update(now, q, v);
  const std::vector<std::string>& joints = controller_.joints();
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (std::find(commanded_.begin(), commanded_.end(), joints[i]) == commanded_.end() ||
        !arbiter_.owns(this, joints[i])) {
      continue;
    }
    const Result r = world_.setPositionTarget(joints[i], last_update_.desired.position[i],
                                              last_update_.desired.velocity[i]);
    if (!r.ok()) {
      ROS_ERROR_STREAM_THROTTLE(1.0, "[" << controller_.config().name << "] " << r.message);
    }
  }
  if (last_update_.finished) {
    finishActive(static_cast<int>(last_update_.result.status), last_update_.result.message,
                 last_update_.state == GoalState::kSucceeded, false);
  }
}

void TrajectoryActionHandler::publishFeedback(const ros::Time& stamp) {
  // The state topic runs while this controller commands its joints (not while another driver, e.g.
  // gripper_cmd, has them).
  const double now = stamp.toSec();
  const bool state_due =
      state_period_ > 0.0 && ownsAny() && (now >= next_state_ || now < next_state_ - state_period_);
  if (last_update_.desired.position.empty() || (!active_ && !state_due)) {
    return;
  }
  // The action feedback and the state topic carry the same fields.
  control_msgs::FollowJointTrajectoryFeedback fb;
  fb.header.stamp = stamp;
  fb.joint_names = controller_.joints();
  fb.desired.positions = last_update_.desired.position;
  fb.desired.velocities = last_update_.desired.velocity;
  fb.desired.accelerations = last_update_.desired.acceleration;
  fb.error.positions = last_update_.error.position;
  fb.error.velocities = last_update_.error.velocity;
  for (std::size_t i = 0; i < fb.joint_names.size(); ++i) {
    fb.actual.positions.push_back(fb.desired.positions[i] - fb.error.positions[i]);
    fb.actual.velocities.push_back(fb.desired.velocities[i] - fb.error.velocities[i]);
  }
  if (active_) {
    active_->publishFeedback(fb);
  }
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

}  // namespace sixdof_sim
