#include "loop_host.h"

#include <algorithm>

namespace sixdof_control {

using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectorySample;
using sixdof_core::TrajectoryUpdate;

void addControllers(const ControllerSetup& setup, ControlLoopConfig& config) {
  for (const TrajectoryControllerSetup& c : setup.trajectory) {
    config.controllers.push_back(c.joints.actuatedConfig(c.config));
  }
  if (setup.gripper) config.grippers.push_back(*setup.gripper);
}

LoopHost::LoopHost(ControlLoop& loop, const ControllerSetup& setup, const std::vector<std::string>& hardware_joints,
                   std::function<double()> ros_now)
    : loop_(loop), ros_now_(std::move(ros_now)) {
  for (const TrajectoryControllerSetup& c : setup.trajectory) joints_.emplace(c.config.name, c.joints);
  if (setup.gripper) {
    const auto it = std::find(hardware_joints.begin(), hardware_joints.end(), setup.gripper->joint);
    gripper_joint_[setup.gripper->name] = static_cast<std::size_t>(it - hardware_joints.begin());
  }
}

double LoopHost::offset() const { return ros_now_() - loop_.now(); }

const ControllerJoints* LoopHost::joints(const std::string& controller) const {
  const auto it = joints_.find(controller);
  return it == joints_.end() ? nullptr : &it->second;
}

TrajectoryResult LoopHost::setGoal(const std::string& controller, const TrajectoryGoal& goal, GoalCallback done) {
  const ControllerJoints* j = joints(controller);
  if (j == nullptr) {
    return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, "unknown controller '" + controller + "'");
  }
  TrajectoryGoal actuated;
  const TrajectoryResult mapped = j->actuatedGoal(goal, actuated);
  if (!mapped.ok()) return mapped;
  // A stamp of 0 starts the trajectory when it is accepted, on any clock.
  if (actuated.start_time != 0.0) actuated.start_time -= offset();
  return loop_.setGoal(controller, actuated, std::move(done));
}

void LoopHost::cancel(const std::string& controller) { loop_.cancel(controller); }

sixdof_core::GripperResult LoopHost::setGripperGoal(const std::string& gripper, const sixdof_core::GripperGoal& goal,
                                                    GripperCallback done) {
  return loop_.setGripperGoal(gripper, goal, std::move(done));
}

void LoopHost::cancelGripper(const std::string& gripper) { loop_.cancelGripper(gripper); }

bool LoopHost::commands(const std::string& controller) const { return loop_.commands(controller); }

std::optional<TrajectorySample> LoopHost::sample(const std::string& controller, double time) const {
  const ControllerJoints* j = joints(controller);
  if (j == nullptr) return std::nullopt;
  const std::optional<TrajectorySample> s = loop_.sample(controller, time - offset());
  if (!s) return std::nullopt;
  return j->expand(*s);
}

std::optional<TrajectoryUpdate> LoopHost::lastUpdate(const std::string& controller) const {
  const ControllerJoints* j = joints(controller);
  if (j == nullptr) return std::nullopt;
  std::optional<TrajectoryUpdate> u = loop_.lastUpdate(controller);
  if (!u || !j->hasMimics()) return u;
  u->desired = j->expand(u->desired);
  u->error = j->expand(u->error, false);
  return u;
}

GripperReading LoopHost::gripperReading(const std::string& gripper) const {
  const auto it = gripper_joint_.find(gripper);
  if (it == gripper_joint_.end()) return {};
  const LoopStatus status = loop_.status();
  return {it->second < status.positions.size() ? status.positions[it->second] : 0.0, 0.0};
}

}  // namespace sixdof_control
