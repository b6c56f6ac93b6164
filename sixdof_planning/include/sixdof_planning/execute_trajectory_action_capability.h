#pragma once
// The execute_trajectory action (MoveIt's execute_trajectory_action_capability): runs a planned trajectory
// through the TrajectoryExecutor.

#include <boost/shared_ptr.hpp>

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class ExecuteTrajectoryActionCapability
    : public ActionCapability<ExecuteTrajectoryActionCapability, moveit_msgs::ExecuteTrajectoryAction> {
 public:
  using ActionCapability::ActionCapability;
  void execute(const boost::shared_ptr<const moveit_msgs::ExecuteTrajectoryGoal>& goal);
};

}  // namespace sixdof_planning
