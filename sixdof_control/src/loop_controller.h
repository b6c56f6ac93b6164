#pragma once
// The controllers as the control loop keeps them (private to control_loop*.cpp).

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "sixdof_control/control_loop.h"

namespace sixdof_control {

struct ControlLoop::Controller {
  sixdof_core::TrajectoryController controller;
  std::vector<std::size_t> joints;  // indices into the hardware's joints, in the controller's order
  GoalCallback done;                // of the active goal
  std::optional<sixdof_core::TrajectoryUpdate> last;
};

struct ControlLoop::Gripper {
  sixdof_core::GripperController controller;
  std::size_t joint;     // index into the hardware's joints
  GripperCallback done;  // of the active goal
  double command = 0.0;  // moving towards the controller's command at the joint's velocity limit
};

namespace loop {

// Calls the goal callbacks collected under the lock.
inline void notify(const std::vector<std::function<void()>>& done) {
  for (const auto& call : done) call();
}

// values[indices[0]], values[indices[1]], ...
inline std::vector<double> pick(const std::vector<double>& values, const std::vector<std::size_t>& indices) {
  std::vector<double> out;
  out.reserve(indices.size());
  for (std::size_t i : indices) out.push_back(values[i]);
  return out;
}

}  // namespace loop

}  // namespace sixdof_control
