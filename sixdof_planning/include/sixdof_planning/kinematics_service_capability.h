#pragma once
// compute_fk and compute_ik (MoveIt's kinematics_service_capability): forward kinematics of named links and
// inverse kinematics of a group's tip, in the context's namespace. Every request gets an error code.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class ForwardKinematicsService {  // compute_fk
 public:
  explicit ForwardKinematicsService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPositionFKRequest& request, sixdof_msgs::GetPositionFKResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class InverseKinematicsService {  // compute_ik
 public:
  explicit InverseKinematicsService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPositionIKRequest& request, sixdof_msgs::GetPositionIKResponse& response);

 private:
  sixdof_msgs::MoveItErrorCodes solve(const sixdof_msgs::PositionIKRequest& request,
                                      sixdof_msgs::RobotState* solution) const;

  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
