#include "sixdof_core/control/gripper_controller.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sixdof_core {

GripperController::GripperController(GripperControllerConfig config) : config_(std::move(config)) {
  const std::string who = "GripperController '" + config_.name + "': ";
  if (config_.joint.empty()) {
    throw std::invalid_argument(who + "no joint");
  }
  if (!std::isfinite(config_.lower) || !std::isfinite(config_.upper) || config_.lower > config_.upper) {
    throw std::invalid_argument(who + "invalid position limits of joint '" + config_.joint + "'");
  }
  if (!(config_.effort_limit > 0.0) || !std::isfinite(config_.effort_limit)) {
    throw std::invalid_argument(who + "joint '" + config_.joint + "' needs a positive effort limit in the URDF");
  }
  if (!(config_.goal_tolerance > 0.0) || !(config_.stall_velocity_threshold > 0.0) ||
      !(config_.stall_timeout >= 0.0) || !std::isfinite(config_.goal_tolerance) ||
      !std::isfinite(config_.stall_velocity_threshold) || !std::isfinite(config_.stall_timeout)) {
    throw std::invalid_argument(
        who + "goal_tolerance and stall_velocity_threshold must be > 0, stall_timeout >= 0 (all finite)");
  }
}

GripperResult GripperController::validate(const GripperGoal& goal) const {
  std::ostringstream s;
  GripperStatus status = GripperStatus::kOk;
  if (!std::isfinite(goal.position) || !std::isfinite(goal.max_effort)) {
    status = GripperStatus::kInvalidArgument;
    s << "position and max_effort must be finite (got " << goal.position << ", " << goal.max_effort << ")";
  } else if (goal.position < config_.lower || goal.position > config_.upper) {
    status = GripperStatus::kOutOfLimits;
    s << "position " << goal.position << " of joint '" << config_.joint << "' is outside its limits ["
      << config_.lower << ", " << config_.upper << "]";
  } else if (goal.max_effort < 0.0) {
    status = GripperStatus::kInvalidArgument;
    s << "max_effort " << goal.max_effort << " is negative (0 means the effort limit " << config_.effort_limit
      << ")";
  } else if (goal.max_effort > config_.effort_limit) {
    status = GripperStatus::kOutOfLimits;
    s << "max_effort " << goal.max_effort << " exceeds the effort limit " << config_.effort_limit << " of joint '"
      << config_.joint << "'";
  }
  return {status, s.str()};
}

GripperResult GripperController::setGoal(const GripperGoal& goal, double now) {
  GripperResult r = validate(goal);
  if (!r.ok()) {
    return r;
  }
  has_command_ = true;
  command_position_ = goal.position;
  command_effort_ = goal.max_effort > 0.0 ? goal.max_effort : config_.effort_limit;
  progress_time_ = now;
  progress_anchored_ = false;
  state_ = GoalState::kActive;
  return r;
}

void GripperController::hold(double position) {
  if (state_ == GoalState::kActive) {
    state_ = GoalState::kCanceled;
  }
  has_command_ = true;
  command_position_ = position;
  command_effort_ = config_.effort_limit;
}

void GripperController::cancel(double actual_position) {
  if (state_ == GoalState::kActive) {
    hold(actual_position);
  }
}

GripperUpdate GripperController::update(double now, double position) {
  if (!has_command_) {
    hold(position);
  }
  GripperUpdate out;
  out.position = position;
  if (state_ == GoalState::kActive) {
    const double distance = std::abs(command_position_ - position);
    if (!progress_anchored_) {
      progress_anchored_ = true;
      progress_distance_ = distance;
    }
    if (distance < config_.goal_tolerance) {
      out.reached_goal = true;
      out.finished = true;
      state_ = GoalState::kSucceeded;
    } else if (progress_distance_ - distance > config_.stall_velocity_threshold * config_.stall_timeout) {
      // Came closer to the target than the threshold speed allows in stall_timeout: not stalled.
      progress_distance_ = distance;
      progress_time_ = now;
    } else if (now - progress_time_ > config_.stall_timeout) {
      out.stalled = true;
      out.finished = true;
      state_ = config_.allow_stalling ? GoalState::kSucceeded : GoalState::kAborted;
    }
  }
  out.command_position = command_position_;
  out.command_max_effort = command_effort_;
  out.state = state_;
  return out;
}

}  // namespace sixdof_core
