#pragma once
// The node's controllers are sixdof_core's (library sixdof_core_control), the ones sixdof_control runs on hardware;
// the names the node uses, in this namespace.

#include "sixdof_core/control/gripper_controller.h"
#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_sim {

using sixdof_core::GoalState;
using sixdof_core::GripperController;
using sixdof_core::GripperControllerConfig;
using sixdof_core::GripperGoal;
using sixdof_core::GripperResult;
using sixdof_core::GripperUpdate;
using sixdof_core::TrajectoryController;
using sixdof_core::TrajectoryControllerConfig;
using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectorySample;
using sixdof_core::TrajectoryUpdate;

}  // namespace sixdof_sim
