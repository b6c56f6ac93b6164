#pragma once
// compute_fk and compute_ik (MoveIt's kinematics_service_capability): forward kinematics of named links and
// inverse kinematics of a group's tip, in the context's namespace. Every request gets an error code.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class ForwardKinematicsService : public ServiceCapability<ForwardKinematicsService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetPositionFKRequest& request, moveit_msgs::GetPositionFKResponse& response);

 private:
  ErrorCode fk(const moveit_msgs::GetPositionFKRequest& request, moveit_msgs::GetPositionFKResponse* response) const;
};

class InverseKinematicsService : public ServiceCapability<InverseKinematicsService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetPositionIKRequest& request, moveit_msgs::GetPositionIKResponse& response);
};

}  // namespace sixdof_planning
