#pragma once
// retime_trajectory: time-optimal parameterization of a given joint path (what moveit_commander's
// retime_trajectory does in-process with MoveIt's TimeOptimalTrajectoryGeneration).

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class RetimeTrajectoryService : public ServiceCapability<RetimeTrajectoryService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const sixdof_msgs::RetimeTrajectoryRequest& request, sixdof_msgs::RetimeTrajectoryResponse& response);

 private:
  ErrorCode retime(const sixdof_msgs::RetimeTrajectoryRequest& request,
                   sixdof_msgs::RetimeTrajectoryResponse* response) const;
};

}  // namespace sixdof_planning
