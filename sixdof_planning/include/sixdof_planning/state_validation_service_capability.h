#pragma once
// check_state_validity (MoveIt's state_validation_service_capability): collisions and joint bounds of a state.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class StateValidityService : public ServiceCapability<StateValidityService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetStateValidityRequest& request, moveit_msgs::GetStateValidityResponse& response);
};

}  // namespace sixdof_planning
