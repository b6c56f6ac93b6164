#pragma once
// retime_trajectory: time-optimal parameterization of a given joint path (what moveit_commander's
// retime_trajectory does in-process with MoveIt's TimeOptimalTrajectoryGeneration).

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class RetimeTrajectoryService {  // retime_trajectory
 public:
  explicit RetimeTrajectoryService(MoveGroupContext* context);
  bool handle(sixdof_msgs::RetimeTrajectoryRequest& request, sixdof_msgs::RetimeTrajectoryResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
