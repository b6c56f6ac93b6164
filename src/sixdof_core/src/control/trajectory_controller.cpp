#include "sixdof_core/control/trajectory_controller.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

namespace sixdof_core {

namespace {

TrajectoryResult fail(TrajectoryErrorCode code, const std::string& message) { return {code, message}; }

bool allFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// Applies a goal's override to a configured tolerance (control_msgs/JointTolerance rules).
void override(double requested, double& value) {
  if (requested > 0.0) {
    value = requested;
  } else if (requested < 0.0) {
    value = 0.0;
  }
}

// The shortest text that reads back as the same double: a position a rounding error past a limit shows as such.
std::string exact(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

}  // namespace

TrajectoryController::TrajectoryController(TrajectoryControllerConfig config) : config_(std::move(config)) {
  const std::size_t n = config_.joints.size();
  const std::string who = "TrajectoryController '" + config_.name + "': ";
  if (n == 0) {
    throw std::invalid_argument(who + "no joints");
  }
  if (std::set<std::string>(config_.joints.begin(), config_.joints.end()).size() != n) {
    throw std::invalid_argument(who + "duplicate joint names");
  }
  if (config_.lower_limits.size() != n || config_.upper_limits.size() != n || config_.path_tolerance.size() != n ||
      config_.goal_tolerance.size() != n) {
    throw std::invalid_argument(who + "limits and tolerances need one value per joint");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isnan(config_.lower_limits[i]) || std::isnan(config_.upper_limits[i]) ||
        config_.lower_limits[i] > config_.upper_limits[i]) {
      throw std::invalid_argument(who + "invalid position limits for joint '" + config_.joints[i] + "'");
    }
    if (!(config_.path_tolerance[i] >= 0.0) || !(config_.goal_tolerance[i] >= 0.0) ||
        !std::isfinite(config_.path_tolerance[i]) || !std::isfinite(config_.goal_tolerance[i])) {
      throw std::invalid_argument(who + "tolerances of joint '" + config_.joints[i] +
                                  "' must be finite and >= 0 (0 = not checked)");
    }
  }
  if (!(config_.goal_time >= 0.0) || !std::isfinite(config_.goal_time)) {
    throw std::invalid_argument(who + "goal_time must be finite and >= 0");
  }
  if (!(config_.stopped_velocity_tolerance >= 0.0) || !std::isfinite(config_.stopped_velocity_tolerance)) {
    throw std::invalid_argument(who + "stopped_velocity_tolerance must be finite and >= 0");
  }
}

std::string TrajectoryController::jointList() const {
  std::string out;
  for (const std::string& j : config_.joints) {
    out += (out.empty() ? "" : ", ") + j;
  }
  return "[" + out + "]";
}

TrajectoryResult TrajectoryController::validateTolerances(const std::vector<JointToleranceOverride>& tolerances,
                                                          const char* what) const {
  for (const JointToleranceOverride& t : tolerances) {
    if (std::find(config_.joints.begin(), config_.joints.end(), t.name) == config_.joints.end()) {
      return fail(TrajectoryErrorCode::kInvalidJoints, std::string(what) + " names joint '" + t.name +
                                                           "', which controller '" + config_.name +
                                                           "' does not control " + jointList());
    }
    for (double v : {t.position, t.velocity, t.acceleration}) {
      if (!std::isfinite(v) || (v < 0.0 && v != -1.0)) {
        std::ostringstream s;
        s << what << " of joint '" << t.name << "' has value " << v
          << " (allowed: > 0 a limit, 0 the default, -1 no limit)";
        return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
      }
    }
  }
  return {};
}

TrajectoryResult TrajectoryController::validate(const TrajectoryGoal& goal, double now) const {
  const std::size_t n = config_.joints.size();
  const std::vector<std::string>& names = goal.joint_names;
  if (!(names.empty() && goal.points.empty())) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (std::find(names.begin(), names.begin() + i, names[i]) != names.begin() + i) {
        return fail(TrajectoryErrorCode::kInvalidJoints, "joint '" + names[i] + "' appears twice in joint_names");
      }
      if (std::find(config_.joints.begin(), config_.joints.end(), names[i]) == config_.joints.end()) {
        return fail(TrajectoryErrorCode::kInvalidJoints, "unknown joint '" + names[i] + "': controller '" +
                                                             config_.name + "' controls " + jointList());
      }
    }
    for (const std::string& j : config_.joints) {
      if (std::find(names.begin(), names.end(), j) == names.end()) {
        return fail(TrajectoryErrorCode::kInvalidJoints, "joint '" + j + "' of controller '" + config_.name +
                                                             "' is missing from joint_names (all of " + jointList() +
                                                             " are required)");
      }
    }
  }
  for (std::size_t p = 0; p < goal.points.size(); ++p) {
    const TrajectoryPoint& pt = goal.points[p];
    std::ostringstream s;
    s << "point " << p << ": ";
    if (pt.positions.size() != n) {
      s << pt.positions.size() << " positions for " << n << " joints";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (!pt.velocities.empty() && pt.velocities.size() != n) {
      s << pt.velocities.size() << " velocities for " << n << " joints (give none or one per joint)";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (!pt.accelerations.empty() && pt.accelerations.size() != n) {
      s << pt.accelerations.size() << " accelerations for " << n << " joints (give none or one per joint)";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (!pt.accelerations.empty() && pt.velocities.empty()) {
      s << "accelerations without velocities";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (!allFinite(pt.positions) || !allFinite(pt.velocities) || !allFinite(pt.accelerations)) {
      s << "non-finite (NaN or inf) position, velocity or acceleration";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (!std::isfinite(pt.time_from_start) || pt.time_from_start < 0.0) {
      s << "time_from_start " << pt.time_from_start << " must be finite and >= 0";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    if (p > 0 && !(pt.time_from_start > goal.points[p - 1].time_from_start)) {
      s << "time_from_start " << pt.time_from_start << " s is not after point " << p - 1 << "'s "
        << goal.points[p - 1].time_from_start << " s (times must strictly increase)";
      return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t c = static_cast<std::size_t>(
          std::find(config_.joints.begin(), config_.joints.end(), names[i]) - config_.joints.begin());
      const double q = pt.positions[i];
      if (q < config_.lower_limits[c] || q > config_.upper_limits[c]) {
        s << "position " << exact(q) << " of joint '" << names[i] << "' is outside its limits ["
          << exact(config_.lower_limits[c]) << ", " << exact(config_.upper_limits[c]) << "]";
        return fail(TrajectoryErrorCode::kInvalidGoal, s.str());
      }
    }
  }
  if (!std::isfinite(goal.start_time) || goal.start_time < 0.0) {
    return fail(TrajectoryErrorCode::kInvalidGoal, "trajectory start time (header stamp) must be finite and >= 0");
  }
  if (!goal.points.empty() && goal.start_time > 0.0 && goal.start_time + goal.points.back().time_from_start < now) {
    std::ostringstream s;
    s << "trajectory ends at " << goal.start_time + goal.points.back().time_from_start
      << " s, before the current time " << now << " s (header stamp too old)";
    return fail(TrajectoryErrorCode::kOldHeaderTimestamp, s.str());
  }
  if (!std::isfinite(goal.goal_time_tolerance)) {
    return fail(TrajectoryErrorCode::kInvalidGoal, "goal_time_tolerance must be finite");
  }
  TrajectoryResult r = validateTolerances(goal.path_tolerance, "path_tolerance");
  if (!r.ok()) {
    return r;
  }
  return validateTolerances(goal.goal_tolerance, "goal_tolerance");
}

TrajectoryResult TrajectoryController::setGoal(const TrajectoryGoal& goal, double now) {
  TrajectoryResult r = validate(goal, now);
  if (!r.ok()) {
    return r;
  }
  if (last_desired_.position.empty()) {
    return fail(TrajectoryErrorCode::kInvalidGoal,
                "controller '" + config_.name + "' has no current state yet (no update or hold before the goal)");
  }
  const std::size_t n = config_.joints.size();
  path_tolerance_.assign(n, StateTolerance{});
  goal_tolerance_.assign(n, StateTolerance{});

  if (goal.points.empty()) {
    // Stop: hold the current command; no tolerance is checked, so the next update succeeds.
    trajectory_.emplace(Trajectory{config_.joints, {{last_desired_.position, {}, {}, now}}});
    goal_time_ = 0.0;
    state_ = GoalState::kActive;
    return {};
  }

  for (std::size_t i = 0; i < n; ++i) {
    path_tolerance_[i].position = config_.path_tolerance[i];
    goal_tolerance_[i].position = config_.goal_tolerance[i];
    goal_tolerance_[i].velocity = config_.stopped_velocity_tolerance;
  }
  const auto index = [this](const std::string& name) {
    return static_cast<std::size_t>(std::find(config_.joints.begin(), config_.joints.end(), name) -
                                    config_.joints.begin());
  };
  for (const JointToleranceOverride& t : goal.path_tolerance) {
    StateTolerance& tol = path_tolerance_[index(t.name)];
    override(t.position, tol.position);
    override(t.velocity, tol.velocity);
    override(t.acceleration, tol.acceleration);
  }
  for (const JointToleranceOverride& t : goal.goal_tolerance) {
    StateTolerance& tol = goal_tolerance_[index(t.name)];
    override(t.position, tol.position);
    override(t.velocity, tol.velocity);
    override(t.acceleration, tol.acceleration);
  }
  goal_time_ = config_.goal_time;
  override(goal.goal_time_tolerance, goal_time_);

  // Reorder the points into the controller's joint order.
  std::vector<std::size_t> perm(n);
  for (std::size_t i = 0; i < n; ++i) {
    perm[index(goal.joint_names[i])] = i;
  }
  const auto reorder = [&perm](const std::vector<double>& v) {
    std::vector<double> out;
    for (std::size_t c = 0; c < perm.size() && !v.empty(); ++c) {
      out.push_back(v[perm[c]]);
    }
    return out;
  };
  const double start = goal.start_time > 0.0 ? goal.start_time : now;
  Trajectory trajectory{config_.joints, {}};
  for (const TrajectoryPoint& p : goal.points) {
    // Points already in the past (old header stamp) are skipped: the bridge below leads to the next one.
    if (start + p.time_from_start < now) {
      continue;
    }
    trajectory.points.push_back(
        {reorder(p.positions), reorder(p.velocities), reorder(p.accelerations), start + p.time_from_start});
  }
  if (trajectory.points.front().time_from_start > now) {
    // Bridge from the current command so that a preempting goal continues smoothly.
    trajectory.points.insert(trajectory.points.begin(),
                             {last_desired_.position, last_desired_.velocity, last_desired_.acceleration, now});
  }
  trajectory_.emplace(std::move(trajectory), config_.lower_limits, config_.upper_limits);
  state_ = GoalState::kActive;
  return {};
}

void TrajectoryController::holdAt(const std::vector<double>& position) {
  trajectory_.emplace(Trajectory{config_.joints, {{position, {}, {}, 0.0}}});
  last_desired_ = trajectory_->sample(0.0);
}

std::optional<TrajectorySample> TrajectoryController::sample(double time) const {
  if (!trajectory_) {
    return std::nullopt;
  }
  return trajectory_->sample(time);
}

void TrajectoryController::hold(const std::vector<double>& position) {
  if (position.size() != config_.joints.size()) {
    throw std::invalid_argument("TrajectoryController::hold: wrong number of positions");
  }
  if (state_ == GoalState::kActive) {
    state_ = GoalState::kCanceled;
  }
  holdAt(position);
}

void TrajectoryController::cancel(const std::vector<double>& actual_position) {
  if (state_ == GoalState::kActive) {
    hold(actual_position);
  }
}

TrajectoryUpdate TrajectoryController::update(double now, const std::vector<double>& actual_position,
                                              const std::vector<double>& actual_velocity) {
  const std::size_t n = config_.joints.size();
  if (actual_position.size() != n || actual_velocity.size() != n) {
    throw std::invalid_argument("TrajectoryController::update: wrong number of actual positions/velocities");
  }
  if (!trajectory_) {
    holdAt(actual_position);
  }
  TrajectoryUpdate out;
  out.desired = trajectory_->sample(now);
  const auto error = [&](const TrajectorySample& desired) {
    TrajectorySample e;
    e.acceleration.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      e.position.push_back(desired.position[i] - actual_position[i]);
      e.velocity.push_back(desired.velocity[i] - actual_velocity[i]);
    }
    return e;
  };
  out.error = error(out.desired);

  // Returns a description of the first violated tolerance, or "" when all hold.
  const auto violation = [&](const std::vector<StateTolerance>& tol) -> std::string {
    for (std::size_t i = 0; i < n; ++i) {
      std::ostringstream s;
      if (tol[i].position > 0.0 && std::abs(out.error.position[i]) > tol[i].position) {
        s << "joint '" << config_.joints[i] << "' position error " << out.error.position[i] << " exceeds "
          << tol[i].position;
      } else if (tol[i].velocity > 0.0 && std::abs(out.error.velocity[i]) > tol[i].velocity) {
        s << "joint '" << config_.joints[i] << "' velocity error " << out.error.velocity[i] << " exceeds "
          << tol[i].velocity;
      }
      if (!s.str().empty()) {
        return s.str();
      }
    }
    return "";
  };

  if (state_ == GoalState::kActive) {
    if (now < trajectory_->endTime()) {
      const std::string v = violation(path_tolerance_);
      if (!v.empty()) {
        std::ostringstream s;
        s << "path tolerance violated at t=" << now << " s: " << v;
        out.result = fail(TrajectoryErrorCode::kPathToleranceViolated, s.str());
        state_ = GoalState::kAborted;
        out.finished = true;
        holdAt(actual_position);
        out.desired = trajectory_->sample(now);
        out.error = error(out.desired);
      }
    } else {
      const std::string v = violation(goal_tolerance_);
      if (v.empty()) {
        state_ = GoalState::kSucceeded;
        out.finished = true;
      } else if (now >= trajectory_->endTime() + goal_time_) {
        std::ostringstream s;
        s << "goal tolerance violated " << now - trajectory_->endTime()
          << " s after the trajectory end (goal_time " << goal_time_ << " s): " << v;
        out.result = fail(TrajectoryErrorCode::kGoalToleranceViolated, s.str());
        state_ = GoalState::kAborted;
        out.finished = true;
      }
    }
  }
  out.state = state_;
  last_desired_ = out.desired;
  return out;
}

}  // namespace sixdof_core
