// ControlLoop's goals, e-stop and queries (the calls other threads make).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "loop_controller.h"

namespace sixdof_control {

using loop::notify;
using loop::pick;
using sixdof_core::GoalState;
using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;
using sixdof_core::TrajectoryPoint;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectorySample;
using sixdof_core::TrajectoryUpdate;

namespace {

TrajectoryResult refuse(const std::string& why) {
  return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, why);
}

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
        s << "point " << p << " gives joint '" << l.joint << "' velocity " << v << ", over its limit "
          << l.max_velocity;
      } else if (std::abs(average) > allowed && (p > 0 || goal.start_time == 0.0)) {
        s << "joint '" << l.joint << "' would move at " << average << " on average "
          << (p == 0 ? std::string("to point 0")
                     : "between points " + std::to_string(p - 1) + " and " + std::to_string(p))
          << ", over its velocity limit " << l.max_velocity;
      }
      if (!s.str().empty()) return s.str();
      previous_q = pt.positions[i];
      previous_t = pt.time_from_start;
    }
  }
  return "";
}

int ControlLoop::controllerIndex(const std::string& name) const { return indexOfController(controllers_, name); }

int ControlLoop::gripperIndex(const std::string& name) const { return indexOfController(grippers_, name); }

// Why no goal is taken now; empty when goals are.
std::string ControlLoop::refusal() const {
  if (status_.state == LoopState::kStopped) return "the control loop is not running";
  if (estop_) return "e-stop engaged: goals are refused until it is released";
  if (status_.state == LoopState::kFault) {
    return "hardware fault: " + status_.fault + " (goals are refused until the fault is cleared)";
  }
  return "";
}

void ControlLoop::endGoal(Controller& c, GoalState state, TrajectoryResult result, Notifications& done) {
  done.emplace_back([callback = std::move(c.done), o = GoalOutcome{c.controller.config().name, state, result}] {
    if (callback) callback(o);
  });
  c.done = nullptr;
}

void ControlLoop::endGoal(Gripper& g, GoalState state, const std::string& message, Notifications& done,
                          bool reached_goal, bool stalled) {
  done.emplace_back([callback = std::move(g.done),
                     o = GripperOutcome{g.controller.config().name, state, message, reached_goal, stalled}] {
    if (callback) callback(o);
  });
  g.done = nullptr;
}

void ControlLoop::claim(std::size_t joint, int controller, int gripper, const std::string& by, Notifications& done) {
  const int previous = commander_[joint];
  const int next = controller >= 0 ? controller : -2 - gripper;
  if (previous == next) return;
  const std::string why = "preempted by " + by;
  if (previous >= 0) {
    Controller& c = controllers_[static_cast<std::size_t>(previous)];
    if (c.controller.active()) {
      c.controller.cancel(pick(status_.positions, c.joints));
      endGoal(c, GoalState::kCanceled, TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, why), done);
    }
  } else if (previous <= -2) {
    Gripper& g = grippers_[static_cast<std::size_t>(-2 - previous)];
    if (g.controller.active()) {
      g.controller.cancel(status_.positions[g.joint]);
      endGoal(g, GoalState::kCanceled, why, done);
    }
  }
  if (gripper >= 0) grippers_[static_cast<std::size_t>(gripper)].command = status_.commands[joint];
  commander_[joint] = next;
}

void ControlLoop::abortAll(GoalState state, TrajectoryErrorCode code, const std::string& message, Notifications& done) {
  for (Controller& c : controllers_) {
    if (!c.controller.active()) continue;
    c.controller.cancel(pick(status_.positions, c.joints));
    endGoal(c, state, TrajectoryResult::failure(code, message), done);
  }
  for (Gripper& g : grippers_) {
    if (!g.controller.active()) continue;
    g.controller.cancel(status_.positions[g.joint]);
    g.command = status_.positions[g.joint];
    endGoal(g, state, message, done);
  }
}

void ControlLoop::holdAll(const std::vector<double>& positions) {
  // A goal accepted since the hold was asked for (between a release and the next read) keeps running: it started
  // from the positions of the last read.
  for (Controller& c : controllers_) {
    if (!c.controller.active()) c.controller.hold(pick(positions, c.joints));
  }
  for (Gripper& g : grippers_) {
    if (g.controller.active()) continue;
    g.controller.hold(positions[g.joint]);
    g.command = positions[g.joint];
  }
}

void ControlLoop::enterFault(const std::string& message, Notifications& done) {
  if (status_.state == LoopState::kFault) return;
  abortAll(GoalState::kAborted, TrajectoryErrorCode::kInvalidGoal, "hardware fault: " + message, done);
  status_.state = LoopState::kFault;
  status_.fault = message;
  hold_ = status_.positions;
}

TrajectoryResult ControlLoop::setGoal(const std::string& controller, const TrajectoryGoal& goal, GoalCallback done) {
  Notifications ended;
  TrajectoryResult result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = controllerIndex(controller);
    if (index < 0) return refuse("unknown controller '" + controller + "'");
    if (const std::string why = refusal(); !why.empty()) return refuse(why);
    Controller& c = controllers_[static_cast<std::size_t>(index)];
    result = c.controller.validate(goal, status_.time);
    if (!result.ok()) return result;
    const std::string problem = limitProblem(goal);
    if (!problem.empty()) return refuse(problem);
    // Joints another controller commanded start from where they are.
    const bool commands_all =
        std::all_of(c.joints.begin(), c.joints.end(), [&](std::size_t j) { return commander_[j] == index; });
    if (!commands_all) c.controller.hold(pick(status_.positions, c.joints));
    const bool preempting = c.controller.active();
    result = c.controller.setGoal(goal, status_.time);
    if (!result.ok()) return result;
    if (preempting) {
      endGoal(c, GoalState::kCanceled,
              TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "preempted by a new goal"), ended);
    }
    for (std::size_t j : c.joints) claim(j, index, -1, "controller '" + controller + "'", ended);
    c.done = std::move(done);
  }
  notify(ended);
  return result;
}

sixdof_core::GripperResult ControlLoop::setGripperGoal(const std::string& gripper, const sixdof_core::GripperGoal& goal,
                                                       GripperCallback done) {
  using sixdof_core::GripperResult;
  using sixdof_core::GripperStatus;
  Notifications ended;
  GripperResult result;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = gripperIndex(gripper);
    if (index < 0) return GripperResult::failure(GripperStatus::kRefused, "unknown gripper '" + gripper + "'");
    if (const std::string why = refusal(); !why.empty()) return GripperResult::failure(GripperStatus::kRefused, why);
    Gripper& g = grippers_[static_cast<std::size_t>(index)];
    result = g.controller.validate(goal);
    if (!result.ok()) return result;
    if (g.controller.active()) endGoal(g, GoalState::kCanceled, "preempted by a new goal", ended);
    claim(g.joint, -1, index, "gripper '" + gripper + "'", ended);
    result = g.controller.setGoal(goal, status_.time);
    g.done = std::move(done);
  }
  notify(ended);
  return result;
}

template <class Entry, class Stop>
void ControlLoop::cancelActive(std::vector<Entry>& entries, const std::string& name, Stop stop) {
  Notifications done;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = indexOfController(entries, name);
    if (index < 0) return;
    Entry& entry = entries[static_cast<std::size_t>(index)];
    if (!entry.controller.active()) return;
    stop(entry, done);
  }
  notify(done);
}

void ControlLoop::cancel(const std::string& controller) {
  cancelActive(controllers_, controller, [this](Controller& c, Notifications& done) {
    c.controller.cancel(pick(status_.positions, c.joints));
    endGoal(c, GoalState::kCanceled, TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "canceled"), done);
  });
}

void ControlLoop::cancelGripper(const std::string& gripper) {
  cancelActive(grippers_, gripper, [this](Gripper& g, Notifications& done) {
    g.controller.cancel(status_.positions[g.joint]);
    g.command = status_.positions[g.joint];
    endGoal(g, GoalState::kCanceled, "canceled", done);
  });
}

void ControlLoop::setEstop(bool engaged) {
  Notifications done;
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
  notify(done);
}

void ControlLoop::clearFault() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (status_.state != LoopState::kFault) return;
  status_.state = estop_ ? LoopState::kEstop : LoopState::kRunning;
  status_.fault.clear();
  rehold_ = true;
  ++clears_;
}

LoopStatus ControlLoop::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

PeriodSummary ControlLoop::statistics() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return statistics_.summary();
}

double ControlLoop::now() const {
  if (running_) return std::chrono::duration<double>(std::chrono::steady_clock::now() - origin_).count();
  std::lock_guard<std::mutex> lock(mutex_);
  return status_.time;
}

bool ControlLoop::commands(const std::string& controller) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const int index = controllerIndex(controller);
  return index >= 0 && std::any_of(controllers_[static_cast<std::size_t>(index)].joints.begin(),
                                   controllers_[static_cast<std::size_t>(index)].joints.end(),
                                   [&](std::size_t j) { return commander_[j] == index; });
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
