#pragma once
// The controllers as the control loop keeps them (private to control_loop*.cpp).

#include <cstddef>
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
  std::size_t joint;      // index into the hardware's joints
  GripperCallback done;   // of the active goal
  double command = 0.0;   // moving towards the controller's command at the joint's velocity limit
};

}  // namespace sixdof_control
