#pragma once
// A controller as the control loop keeps it (private to control_loop*.cpp).

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

}  // namespace sixdof_control
