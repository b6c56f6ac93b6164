#include "sixdof_planning/trajectory_execution.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <sixdof_core/trajectory.h>

#include "sixdof_planning/conversions.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {

// How long to wait for a controller's action server before giving up on it.
constexpr double kServerWaitSeconds = 1.0;
// Wall-clock seconds of silence that end an execution once the wall clock is past its time limit.
constexpr double kLateSilence = 0.2;
// Wall-clock seconds a succeeded execution waits for joint_states to show the trajectory's end (MoveIt's
// waitForRobotToStop's bound).
constexpr double kEndWaitSeconds = 1.0;

std::string followErrorName(int code) {
  using R = control_msgs::FollowJointTrajectoryResult;
  static const std::map<int, std::string> kNames = {
      {R::SUCCESSFUL, "SUCCESSFUL"},
      {R::INVALID_GOAL, "INVALID_GOAL"},
      {R::INVALID_JOINTS, "INVALID_JOINTS"},
      {R::OLD_HEADER_TIMESTAMP, "OLD_HEADER_TIMESTAMP"},
      {R::PATH_TOLERANCE_VIOLATED, "PATH_TOLERANCE_VIOLATED"},
      {R::GOAL_TOLERANCE_VIOLATED, "GOAL_TOLERANCE_VIOLATED"},
  };
  const auto name = kNames.find(code);
  return name != kNames.end() ? name->second : "error " + std::to_string(code);
}

std::string str(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Seconds to 0.1 s ("3.2"); infinity reads "inf" (never heard of).
std::string seconds(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << value;
  return out.str();
}

// The first of the trajectory's joints whose position (`position(name)`) is more than `tolerance` from `point` (a joint
// without limits modulo 2 pi), as its index; -1 when none is.
template <typename Position>
int deviatingJoint(const sixdof_core::RobotModel& model, const trajectory_msgs::JointTrajectory& trajectory,
                   const trajectory_msgs::JointTrajectoryPoint& point, double tolerance, const Position& position) {
  for (size_t i = 0; i < trajectory.joint_names.size(); ++i) {
    const auto& joint = model.joint(trajectory.joint_names[i]);
    double delta = point.positions[i] - position(joint.name);
    if (!joint.limits.bounded) delta = std::remainder(delta, 2.0 * M_PI);
    if (!(std::abs(delta) <= tolerance)) return static_cast<int>(i);  // NaN (never received) too
  }
  return -1;
}

}  // namespace

TrajectoryExecutor::TrajectoryExecutor(MoveGroupContext* context) : context_(context) {
  for (const auto& controller : context_->config().controllers) {
    // Callbacks are served by the node's spinner, not a thread per client.
    clients_[controller.name] = std::make_unique<Client>(context_->nodeHandle(), controller.actionName(), false);
    action_names_[controller.name] = controller.actionName();
  }
}

ErrorCode TrajectoryExecutor::validate(const trajectory_msgs::JointTrajectory& trajectory,
                                       const std::string& source) const {
  const auto& model = *context_->model();
  const std::string problem = sixdof_core::validateTrajectory(fromJointTrajectory(trajectory));
  if (!problem.empty()) return makeError(ErrorCode::INVALID_MOTION_PLAN, "invalid trajectory: " + problem, source);
  return validateTrajectoryJoints(model, trajectory.joint_names, source);
}

ErrorCode TrajectoryExecutor::split(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source,
                                    std::map<std::string, trajectory_msgs::JointTrajectory>* parts) const {
  const auto& model = *context_->model();
  std::map<std::string, size_t> column;
  for (size_t i = 0; i < trajectory.joint_names.size(); ++i) column[trajectory.joint_names[i]] = i;
  std::set<std::string> covered;
  for (const auto& controller : context_->config().controllers) {
    // For each controller joint: the trajectory column it follows and the mimic factors (1, 0 for itself).
    struct Source {
      size_t column;
      double multiplier;
      double offset;
    };
    std::vector<std::pair<std::string, Source>> joints;
    for (const auto& joint : controller.joints) {
      const auto& jm = model.joint(joint);
      if (column.count(joint)) {
        joints.push_back({joint, {column.at(joint), 1.0, 0.0}});
        covered.insert(joint);
      } else if (jm.mimic && column.count(jm.mimic->joint)) {
        joints.push_back({joint, {column.at(jm.mimic->joint), jm.mimic->multiplier, jm.mimic->offset}});
      }
    }
    if (joints.empty()) continue;
    trajectory_msgs::JointTrajectory part;
    part.header = trajectory.header;
    for (const auto& j : joints) part.joint_names.push_back(j.first);
    for (const auto& point : trajectory.points) {
      trajectory_msgs::JointTrajectoryPoint p;
      p.time_from_start = point.time_from_start;
      for (const auto& j : joints) {
        const Source& s = j.second;
        p.positions.push_back(s.multiplier * point.positions[s.column] + s.offset);
        if (!point.velocities.empty()) p.velocities.push_back(s.multiplier * point.velocities[s.column]);
        if (!point.accelerations.empty()) p.accelerations.push_back(s.multiplier * point.accelerations[s.column]);
      }
      part.points.push_back(p);
    }
    (*parts)[controller.name] = part;
  }
  for (const auto& name : trajectory.joint_names) {
    if (!covered.count(name)) {
      return makeError(ErrorCode::CONTROL_FAILED, "no controller in controller_list handles joint '" + name + "'",
                       source);
    }
  }
  return makeSuccess(source);
}

void TrajectoryExecutor::cancelAll(const std::map<std::string, trajectory_msgs::JointTrajectory>& parts) {
  for (const auto& part : parts) {
    auto& client = *clients_.at(part.first);
    if (!client.getState().isDone()) client.cancelGoal();
  }
}

ErrorCode TrajectoryExecutor::execute(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source,
                                      const std::function<bool()>& preempt_requested) {
  std::lock_guard<std::mutex> lock(execution_mutex_);
  ErrorCode code = validate(trajectory, source);
  if (!isSuccess(code)) return code;
  std::map<std::string, trajectory_msgs::JointTrajectory> parts;
  code = split(trajectory, source, &parts);
  if (!isSuccess(code)) return code;

  // The robot must be where the trajectory starts (MoveIt's allowed_start_tolerance).
  // Executing needs a live robot: a state older than joint_state_timeout is where the robot was, not where it is.
  // Like MoveIt's waitForCurrentState, a fresh one is awaited for joint_state_timeout (e.g. a restarted simulator's
  // first messages on their way).
  const double stale = context_->config().joint_state_timeout;
  const ros::WallTime state_deadline = ros::WallTime::now() + ros::WallDuration(stale);
  double age = context_->stateMonitor().liveness().joint_states_age;
  while (age > stale && ros::WallTime::now() < state_deadline && ros::ok()) {
    ros::WallDuration(0.01).sleep();
    age = context_->stateMonitor().liveness().joint_states_age;
  }
  if (age > stale) {
    return makeError(ErrorCode::CONTROL_FAILED,
                     "no current robot state: joint_states stale for " + seconds(age) + " s", source);
  }
  sixdof_core::RobotState current(context_->model());
  code = context_->currentState(source, &current);
  if (!isSuccess(code)) return code;
  const double tolerance = context_->config().start_state_tolerance;
  if (tolerance > 0.0) {
    const auto& first = trajectory.points.front();
    const int i = deviatingJoint(*context_->model(), trajectory, first, tolerance,
                                 [&](const std::string& name) { return current.jointPosition(name); });
    if (i >= 0) {
      const std::string& name = trajectory.joint_names[i];
      return makeError(ErrorCode::CONTROL_FAILED,
                       "Invalid trajectory: start point deviates from current robot state more than " + str(tolerance) +
                           " at joint '" + name + "' (trajectory " + str(first.positions[i]) + ", current " +
                           str(current.jointPosition(name)) + ")",
                       source);
    }
  }

  for (const auto& part : parts) {
    if (!waitForServer(part.first)) {
      return makeError(ErrorCode::CONTROL_FAILED,
                       "controller '" + part.first + "': action server '" + serverName(part.first) +
                           "' is not available",
                       source);
    }
  }
  const double expected = trajectory.points.back().time_from_start.toSec();
  const double allowed =
      expected * context_->config().execution_duration_scaling + context_->config().execution_goal_margin;
  for (const auto& part : parts) {
    control_msgs::FollowJointTrajectoryGoal goal;
    goal.trajectory = part.second;
    goal.trajectory.header.stamp = ros::Time(0);  // start now
    clients_.at(part.first)->sendGoal(goal);
  }
  // The time limit holds on both clocks (it ends when the smaller elapsed time passes it): a simulator running faster
  // than real time (headless) would otherwise spend the whole margin on message latency, and one running slower than
  // real time is judged on its own clock. A controller that stops reporting (its action server gone, /clock standing
  // still, joint_states silent) stops both from mattering, so it is caught on the wall clock by the watchdog: within
  // execution_watchdog_timeout, and within kLateSilence once the wall clock is past the limit (a slow simulator
  // keeps going only while it is visibly alive), so a dead controller ends the execution by the limit (+ kLateSilence
  // when it died in the last moment of a slow simulation).
  const ros::Time start = ros::Time::now();
  const ros::WallTime wall_start = ros::WallTime::now();
  const double watchdog = context_->config().execution_watchdog_timeout;
  ros::WallRate rate(100.0);
  while (ros::ok()) {
    if (preempt_requested && preempt_requested()) {
      cancelAll(parts);
      return makeError(ErrorCode::PREEMPTED, "execution preempted by the client", source);
    }
    bool all_done = true;
    for (const auto& part : parts) {
      auto& client = *clients_.at(part.first);
      const auto state = client.getState();
      if (!state.isDone()) {
        all_done = false;
        continue;
      }
      const auto result = client.getResult();
      const bool succeeded = state == actionlib::SimpleClientGoalState::SUCCEEDED && result &&
                             result->error_code == control_msgs::FollowJointTrajectoryResult::SUCCESSFUL;
      if (!succeeded) {
        cancelAll(parts);
        std::string detail = "goal " + state.toString();
        if (result) detail += ", " + followErrorName(result->error_code) + ": " + result->error_string;
        return makeError(ErrorCode::CONTROL_FAILED, "controller '" + part.first + "' failed (" + detail + ")",
                         source);
      }
    }
    if (all_done) {
      waitForEnd(trajectory, source);
      return makeSuccess(source, "executed " + str(expected) + " s trajectory on " + std::to_string(parts.size()) +
                                     " controller(s)");
    }
    const double wall_elapsed = (ros::WallTime::now() - wall_start).toSec();
    const double silence = wall_elapsed > allowed ? std::min(watchdog, kLateSilence) : watchdog;
    const std::string problem = controllerSilence(parts, silence);
    if (!problem.empty()) {
      cancelAll(parts);
      ROS_ERROR_STREAM(source << ": " << problem << ": execution stopped after " << seconds(wall_elapsed)
                              << " s (wall clock)");
      return makeError(ErrorCode::CONTROL_FAILED,
                       problem + ": execution stopped after " + seconds(wall_elapsed) + " s (wall clock)", source);
    }
    if (std::min((ros::Time::now() - start).toSec(), wall_elapsed) > allowed) {
      cancelAll(parts);
      return makeError(ErrorCode::TIMED_OUT,
                       "Controller is taking too long to execute trajectory (the expected upper bound for the "
                       "trajectory execution was " +
                           str(allowed) + " seconds). Stopping trajectory.",
                       source);
    }
    rate.sleep();
  }
  cancelAll(parts);
  return makeError(ErrorCode::PREEMPTED, "node shutting down", source);
}

void TrajectoryExecutor::waitForEnd(const trajectory_msgs::JointTrajectory& trajectory,
                                    const std::string& source) const {
  const double tolerance = context_->config().start_state_tolerance;
  if (tolerance <= 0.0) return;  // nothing compares the next start with the current state (MoveIt skips it too)
  const auto& model = *context_->model();
  const auto& end = trajectory.points.back();
  // Trajectory joints are active joints (validate()): a joint never received counts as far away.
  const auto at_end = [&](const std::map<std::string, double>& positions) {
    return deviatingJoint(model, trajectory, end, tolerance, [&](const std::string& name) {
             const auto it = positions.find(name);
             return it != positions.end() ? it->second : std::numeric_limits<double>::infinity();
           }) < 0;
  };
  if (!context_->stateMonitor().waitForPositions(at_end, kEndWaitSeconds)) {
    ROS_WARN_STREAM(source << ": the controllers report success but joint_states have not shown the trajectory's end "
                              "within "
                           << kEndWaitSeconds << " s: the next request may start from an older state");
  }
}

std::string TrajectoryExecutor::serverName(const std::string& controller) const {
  return context_->nodeHandle().resolveName(action_names_.at(controller));
}

bool TrajectoryExecutor::waitForServer(const std::string& controller) {
  // On the wall clock: actionlib's waitForServer counts ROS time, which never passes while /clock stands still.
  auto& client = *clients_.at(controller);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kServerWaitSeconds);
  while (!client.isServerConnected()) {
    if (ros::WallTime::now() > deadline || !ros::ok()) return false;
    ros::WallDuration(0.01).sleep();
  }
  return true;
}

std::string TrajectoryExecutor::controllerSilence(const std::map<std::string, trajectory_msgs::JointTrajectory>& parts,
                                                  double limit) const {
  for (const auto& part : parts) {
    if (!clients_.at(part.first)->isServerConnected()) {
      return "controller '" + part.first + "': action server '" + serverName(part.first) + "' lost";
    }
  }
  const StateLiveness live = context_->stateMonitor().liveness();
  if (live.clock_still > limit) {
    return "/clock has not advanced for " + seconds(live.clock_still) + " s (is the simulator running?)";
  }
  if (live.joint_states_age > limit) {
    return "joint_states stale for " + seconds(live.joint_states_age) + " s";
  }
  return "";
}

}  // namespace sixdof_planning
