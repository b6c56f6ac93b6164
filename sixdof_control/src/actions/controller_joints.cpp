#include "sixdof_control/controller_joints.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sixdof_control {

using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectorySample;

namespace {

const RobotJoint* findJoint(const std::vector<RobotJoint>& robot, const std::string& name) {
  for (const RobotJoint& j : robot) {
    if (j.name == name) return &j;
  }
  return nullptr;
}

std::string list(const std::vector<std::string>& names) {
  std::string text = "[";
  for (const std::string& n : names) text += (text.size() > 1 ? ", " : "") + n;
  return text + "]";
}

// values without the entries at `drop` (indices into it, any order).
std::vector<double> without(const std::vector<double>& values, const std::vector<std::size_t>& drop) {
  std::vector<double> out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::find(drop.begin(), drop.end(), i) == drop.end()) out.push_back(values[i]);
  }
  return out;
}

}  // namespace

ControllerJoints::ControllerJoints(const std::string& controller, const std::vector<std::string>& joints,
                                   const std::vector<RobotJoint>& robot)
    : controller_(controller), joints_(joints) {
  for (const std::string& name : joints_) {
    const RobotJoint* joint = findJoint(robot, name);
    if (joint == nullptr) {
      throw std::invalid_argument("controller '" + controller_ + "': joint '" + name +
                                  "' is not a moving joint of the robot");
    }
    if (joint->mimic_of.empty()) {
      actuated_index_.push_back(static_cast<int>(actuated_.size()));
      actuated_.push_back(name);
      continue;
    }
    actuated_index_.push_back(-1);
    const auto master = std::find(joints_.begin(), joints_.end(), joint->mimic_of);
    if (master == joints_.end()) {
      throw std::invalid_argument("controller '" + controller_ + "': joint '" + name + "' mimics '" + joint->mimic_of +
                                  "', which the controller must then also contain");
    }
    mimics_.push_back({actuated_index_.size() - 1, static_cast<std::size_t>(master - joints_.begin()),
                       joint->mimic_multiplier, joint->mimic_offset});
  }
}

std::string ControllerJoints::checkMimics(const TrajectoryGoal& goal) const {
  const auto position = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(goal.joint_names.begin(), goal.joint_names.end(), name) -
                                    goal.joint_names.begin());
  };
  for (const Mimic& m : mimics_) {
    const std::size_t ji = position(joints_[m.joint]);
    const std::size_t mi = position(joints_[m.master]);
    if (ji == goal.joint_names.size() || mi == goal.joint_names.size()) continue;
    for (std::size_t p = 0; p < goal.points.size(); ++p) {
      const std::vector<double>& q = goal.points[p].positions;
      if (q.size() != goal.joint_names.size()) continue;
      const double expected = m.multiplier * q[mi] + m.offset;
      if (!(std::abs(q[ji] - expected) <= 1e-6)) {
        std::ostringstream s;
        s << "point " << p << ": joint '" << joints_[m.joint] << "' mimics '" << joints_[m.master] << "' and must be "
          << expected << ", got " << q[ji];
        return s.str();
      }
    }
  }
  return "";
}

TrajectoryResult ControllerJoints::actuatedGoal(const TrajectoryGoal& goal, TrajectoryGoal& actuated) const {
  actuated = goal;
  if (mimics_.empty() || (goal.joint_names.empty() && goal.points.empty())) return {};
  std::vector<std::size_t> drop;
  for (const Mimic& m : mimics_) {
    const auto it = std::find(goal.joint_names.begin(), goal.joint_names.end(), joints_[m.joint]);
    if (it == goal.joint_names.end()) {
      return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidJoints,
                                       "joint '" + joints_[m.joint] + "' of controller '" + controller_ +
                                           "' is missing from joint_names (all of " + list(joints_) + " are required)");
    }
    drop.push_back(static_cast<std::size_t>(it - goal.joint_names.begin()));
  }
  const std::size_t n = goal.joint_names.size();
  actuated.joint_names.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (std::find(drop.begin(), drop.end(), i) == drop.end()) actuated.joint_names.push_back(goal.joint_names[i]);
  }
  for (std::size_t p = 0; p < goal.points.size(); ++p) {
    const sixdof_core::TrajectoryPoint& in = goal.points[p];
    for (const std::vector<double>* values : {&in.positions, &in.velocities, &in.accelerations}) {
      if (values->size() != n && !(values != &in.positions && values->empty())) {
        std::ostringstream s;
        s << "point " << p << " has " << values->size() << " "
          << (values == &in.positions    ? "positions"
              : values == &in.velocities ? "velocities"
                                         : "accelerations")
          << " for " << n << " joints";
        return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, s.str());
      }
    }
    sixdof_core::TrajectoryPoint& out = actuated.points[p];
    out.positions = without(in.positions, drop);
    out.velocities = without(in.velocities, drop);
    out.accelerations = without(in.accelerations, drop);
  }
  // A mimic joint is not measured on hardware: its master's tolerances apply to it.
  const auto actuated_only = [&](std::vector<sixdof_core::JointToleranceOverride>& tolerances) {
    tolerances.erase(std::remove_if(tolerances.begin(), tolerances.end(),
                                    [&](const sixdof_core::JointToleranceOverride& t) {
                                      return std::find(actuated_.begin(), actuated_.end(), t.name) == actuated_.end() &&
                                             std::find(joints_.begin(), joints_.end(), t.name) != joints_.end();
                                    }),
                     tolerances.end());
  };
  actuated_only(actuated.path_tolerance);
  actuated_only(actuated.goal_tolerance);
  return {};
}

sixdof_core::TrajectoryControllerConfig ControllerJoints::actuatedConfig(
    const sixdof_core::TrajectoryControllerConfig& config) const {
  if (config.joints != joints_) {
    throw std::invalid_argument("controller '" + controller_ + "': the config's joints are not the controller's");
  }
  sixdof_core::TrajectoryControllerConfig out = config;
  const auto actuated = [&](const std::vector<double>& values) {
    std::vector<double> kept;
    for (std::size_t i = 0; i < values.size() && i < joints_.size(); ++i) {
      if (actuated_index_[i] >= 0) kept.push_back(values[i]);
    }
    return kept;
  };
  out.joints = actuated_;
  out.lower_limits = actuated(config.lower_limits);
  out.upper_limits = actuated(config.upper_limits);
  out.path_tolerance = actuated(config.path_tolerance);
  out.goal_tolerance = actuated(config.goal_tolerance);
  return out;
}

TrajectorySample ControllerJoints::expand(const TrajectorySample& actuated, bool offsets) const {
  if (mimics_.empty()) return actuated;
  TrajectorySample out;
  const auto fill = [&](const std::vector<double>& from, std::vector<double>& to, bool with_offset) {
    if (from.empty()) return;
    to.assign(joints_.size(), 0.0);
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      if (actuated_index_[i] >= 0) to[i] = from[static_cast<std::size_t>(actuated_index_[i])];
    }
    for (const Mimic& m : mimics_) to[m.joint] = m.multiplier * to[m.master] + (with_offset ? m.offset : 0.0);
  };
  fill(actuated.position, out.position, offsets);
  fill(actuated.velocity, out.velocity, false);
  fill(actuated.acceleration, out.acceleration, false);
  return out;
}

}  // namespace sixdof_control
