#pragma once
// check_state_validity (MoveIt's state_validation_service_capability): collisions and joint bounds of a state.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class StateValidityService {  // check_state_validity
 public:
  explicit StateValidityService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetStateValidityRequest& request, sixdof_msgs::GetStateValidityResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
