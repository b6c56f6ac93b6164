#pragma once
// The execute_trajectory action (MoveIt's execute_trajectory_action_capability): runs a planned trajectory
// through the TrajectoryExecutor.

#include <memory>

#include <boost/shared_ptr.hpp>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class ExecuteTrajectoryActionCapability {  // action execute_trajectory
 public:
  ExecuteTrajectoryActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor);
  ~ExecuteTrajectoryActionCapability();

 private:
  void execute(const boost::shared_ptr<const sixdof_msgs::ExecuteTrajectoryGoal>& goal);

  MoveGroupContext* context_;
  TrajectoryExecutor* executor_;
  std::unique_ptr<actionlib::SimpleActionServer<sixdof_msgs::ExecuteTrajectoryAction>> server_;
};

}  // namespace sixdof_planning
