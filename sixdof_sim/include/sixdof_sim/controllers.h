#pragma once
// The node's controllers are sixdof_core's (library sixdof_core_control), the ones sixdof_control runs on hardware.

#include "sixdof_core/control/gripper_controller.h"
#include "sixdof_core/control/trajectory_controller.h"
