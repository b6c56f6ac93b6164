#include "sixdof_rviz/trajectory_animation.h"

#include <algorithm>
#include <cmath>

namespace sixdof_rviz {

std::optional<TrajectoryStates> toTrajectoryStates(const moveit_msgs::DisplayTrajectory& msg, std::string* error) {
  const auto& start = msg.trajectory_start.joint_state;
  if (start.position.size() != start.name.size()) {
    *error = "trajectory_start has " + std::to_string(start.position.size()) + " positions for " +
             std::to_string(start.name.size()) + " joints";
    return std::nullopt;
  }
  if (!msg.trajectory_start.multi_dof_joint_state.joint_names.empty()) {
    *error = "trajectory_start has multi-DOF joints ('" + msg.trajectory_start.multi_dof_joint_state.joint_names[0] +
             "'), which are not supported";
    return std::nullopt;
  }
  TrajectoryStates out;
  JointValues state;
  for (size_t i = 0; i < start.name.size(); ++i) state[start.name[i]] = start.position[i];
  double offset = 0.0;
  for (size_t t = 0; t < msg.trajectory.size(); ++t) {
    const auto& multi_dof = msg.trajectory[t].multi_dof_joint_trajectory;
    if (!multi_dof.joint_names.empty() || !multi_dof.points.empty()) {
      *error = "trajectory " + std::to_string(t) + " has a multi_dof_joint_trajectory, which is not supported";
      return std::nullopt;
    }
    const auto& jt = msg.trajectory[t].joint_trajectory;
    double last = 0.0;
    for (size_t p = 0; p < jt.points.size(); ++p) {
      const auto& point = jt.points[p];
      if (point.positions.size() != jt.joint_names.size()) {
        *error = "trajectory " + std::to_string(t) + " point " + std::to_string(p) + " has " +
                 std::to_string(point.positions.size()) + " positions for " + std::to_string(jt.joint_names.size()) +
                 " joints";
        return std::nullopt;
      }
      const double time = point.time_from_start.toSec();
      if (!std::isfinite(time) || time < last) {
        *error = "trajectory " + std::to_string(t) + " point " + std::to_string(p) + " goes back in time";
        return std::nullopt;
      }
      last = time;
      for (size_t j = 0; j < jt.joint_names.size(); ++j) state[jt.joint_names[j]] = point.positions[j];
      out.states.push_back(state);
      out.times.push_back(offset + time);
    }
    offset += last;
  }
  if (out.states.empty()) {
    *error = "the trajectory has no points";
    return std::nullopt;
  }
  return out;
}

bool TrajectoryAnimation::offer(TrajectoryStates states, bool interrupt) {
  if (interrupt || empty() || finished_) {
    start(std::move(states));
    return true;
  }
  pending_ = std::move(states);
  return false;
}

void TrajectoryAnimation::start(TrajectoryStates states) {
  states_ = std::move(states);
  pending_.reset();
  elapsed_ = 0.0;
  finished_ = states_.states.empty();
  ++generation_;
}

void TrajectoryAnimation::clear() { start(TrajectoryStates{}); }

std::optional<size_t> TrajectoryAnimation::advance(double dt, bool loop, std::optional<double> state_time) {
  if (finished_ && pending_) start(*std::move(pending_));
  if (states_.states.empty()) return std::nullopt;
  const size_t last = states_.states.size() - 1;
  if (finished_) return last;
  elapsed_ += dt;
  // With a fixed display time every state, the last included, is shown for that long.
  const double total = state_time ? *state_time * static_cast<double>(last + 1) : states_.times.back();
  if (elapsed_ > total) {
    if (pending_) {
      start(*std::move(pending_));
      return 0;
    }
    if (loop) {
      elapsed_ = 0.0;
      return 0;
    }
    finished_ = true;
    return last;
  }
  if (state_time) return std::min(last, static_cast<size_t>(elapsed_ / *state_time));
  auto it = std::upper_bound(states_.times.begin(), states_.times.end(), elapsed_);
  return it == states_.times.begin() ? 0 : static_cast<size_t>(it - states_.times.begin()) - 1;
}

}  // namespace sixdof_rviz
