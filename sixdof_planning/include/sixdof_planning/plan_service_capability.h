#pragma once
// plan_kinematic_path (MoveIt's plan_service_capability): one MotionPlanRequest through MotionPlanner.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class MotionPlanService : public ServiceCapability<MotionPlanService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetMotionPlanRequest& request, moveit_msgs::GetMotionPlanResponse& response);
};

}  // namespace sixdof_planning
