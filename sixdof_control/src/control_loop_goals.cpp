// ControlLoop's goals, e-stop and queries (the calls other threads make).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "loop_controller.h"

namespace sixdof_control {

using sixdof_core::GoalState;
using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;
using sixdof_core::TrajectoryPoint;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectorySample;
using sixdof_core::TrajectoryUpdate;
using Done = std::vector<std::pair<GoalCallback, GoalOutcome>>;

namespace {

TrajectoryResult refuse(const std::string& why) { return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, why); }

}  // namespace

// Empty when the goal's points and the segments between them (from the current positions to a first point in the
// future too) respect the joints' velocity limits, and its first point at time 0 is the current state.
std::string ControlLoop::limitProblem(const TrajectoryGoal& goal) const {
  const std::vector<TrajectoryPoint>& points = goal.points;
  if (points.empty()) return "";
  for (std::size_t i = 0; i < goal.joint_names.size(); ++i) {
    const auto it = std::find(config_.joints.begin(), config_.joints.end(), goal.joint_names[i]);
    const JointLimit& l = config_.limits[static_cast<std::size_t>(it - config_.joints.begin())];
    const double current = status_.positions[static_cast<std::size_t>(it - config_.joints.begin())];
    std::ostringstream s;
    const double starts_at = points.front().positions[i];
    if (points.front().time_from_start == 0.0 && std::abs(starts_at - current) > config_.start_tolerance) {
      s << "the trajectory starts joint '" << l.joint << "' at " << starts_at << ", " << starts_at - current
        << " away from its current position " << current << " (start_tolerance " << config_.start_tolerance << ")";
      return s.str();
    }
    if (!l.has_velocity_limits) continue;
    const double allowed = l.max_velocity * (1.0 + config_.velocity_tolerance);
    double previous_q = current;
    double previous_t = 0.0;
    for (std::size_t p = 0; p < points.size(); ++p) {
      const TrajectoryPoint& pt = points[p];
      const double v = pt.velocities.empty() ? 0.0 : pt.velocities[i];
      const double dt = pt.time_from_start - previous_t;
      const double average = dt > 0.0 ? (pt.positions[i] - previous_q) / dt : 0.0;
      if (std::abs(v) > allowed) {
        s << "point " << p << " gives joint '" << l.joint << "' velocity " << v << ", over its limit " << l.max_velocity;
      } else if (std::abs(average) > allowed && (p > 0 || goal.start_time == 0.0)) {
        s << "joint '" << l.joint << "' would move at " << average << " on average "
          << (p == 0 ? std::string("to point 0") : "between points " + std::to_string(p - 1) + " and " +
                                                         std::to_string(p))
          << ", over its velocity limit " << l.max_velocity;
      }
      if (!s.str().empty()) return s.str();
      previous_q = pt.positions[i];
      previous_t = pt.time_from_start;
    }
  }
  return "";
}

TrajectoryResult ControlLoop::setGoal(const std::string& controller, const TrajectoryGoal& goal, GoalCallback done) {
  Done ended;
  TrajectoryResult result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = controllerIndex(controller);
    if (index < 0) return refuse("unknown controller '" + controller + "'");
    Controller& c = controllers_[static_cast<std::size_t>(index)];
    if (status_.state == LoopState::kStopped) return refuse("the control loop is not running");
    if (estop_) return refuse("e-stop engaged: goals are refused until it is released");
    if (status_.state == LoopState::kFault) {
      return refuse("hardware fault: " + status_.fault + " (goals are refused until the fault is cleared)");
    }
    result = c.controller.validate(goal, status_.time);
    if (!result.ok()) return result;
    const std::string problem = limitProblem(goal);
    if (!problem.empty()) return refuse(problem);
    const bool preempting = c.controller.active();
    result = c.controller.setGoal(goal, status_.time);
    if (!result.ok()) return result;
    if (preempting) {
      ended.emplace_back(std::move(c.done),
                         GoalOutcome{controller, GoalState::kCanceled,
                                     TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "preempted by a new goal")});
    }
    c.done = std::move(done);
  }
  for (auto& [callback, outcome] : ended) {
    if (callback) callback(outcome);
  }
  return result;
}

void ControlLoop::cancel(const std::string& controller) {
  GoalCallback callback;
  GoalOutcome outcome{controller, GoalState::kCanceled,
                      TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "canceled")};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = controllerIndex(controller);
    if (index < 0) return;
    Controller& c = controllers_[static_cast<std::size_t>(index)];
    if (!c.controller.active()) return;
    std::vector<double> actual;
    for (std::size_t j : c.joints) actual.push_back(status_.positions[j]);
    c.controller.cancel(actual);
    callback = std::move(c.done);
    c.done = nullptr;
  }
  if (callback) callback(outcome);
}

void ControlLoop::setEstop(bool engaged) {
  Done done;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state == LoopState::kStopped || engaged == estop_) return;
    estop_ = engaged;
    if (engaged) {
      abortAll(GoalState::kAborted, TrajectoryErrorCode::kInvalidGoal, "e-stop engaged", done);
      if (status_.state == LoopState::kRunning) status_.state = LoopState::kEstop;
    } else if (status_.state == LoopState::kEstop) {
      status_.state = LoopState::kRunning;
      rehold_ = true;
    }
  }
  for (auto& [callback, outcome] : done) {
    if (callback) callback(outcome);
  }
}

void ControlLoop::clearFault() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (status_.state != LoopState::kFault) return;
  status_.state = estop_ ? LoopState::kEstop : LoopState::kRunning;
  status_.fault.clear();
  rehold_ = true;
}

LoopStatus ControlLoop::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

PeriodSummary ControlLoop::statistics() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return statistics_.summary();
}

std::optional<TrajectorySample> ControlLoop::sample(const std::string& controller, double time) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const int index = controllerIndex(controller);
  if (index < 0) return std::nullopt;
  return controllers_[static_cast<std::size_t>(index)].controller.sample(time);
}

std::optional<TrajectoryUpdate> ControlLoop::lastUpdate(const std::string& controller) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const int index = controllerIndex(controller);
  if (index < 0) return std::nullopt;
  return controllers_[static_cast<std::size_t>(index)].last;
}

}  // namespace sixdof_control
