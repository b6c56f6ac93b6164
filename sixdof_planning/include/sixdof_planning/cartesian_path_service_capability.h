#pragma once
// compute_cartesian_path (MoveIt's cartesian_path_service_capability): straight tip lines through waypoints.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class CartesianPathService : public ServiceCapability<CartesianPathService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetCartesianPathRequest& request, moveit_msgs::GetCartesianPathResponse& response);
};

}  // namespace sixdof_planning
