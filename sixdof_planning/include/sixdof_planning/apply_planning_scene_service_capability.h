#pragma once
// apply_planning_scene (MoveIt's apply_planning_scene_service_capability): a scene diff, all or nothing.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class ApplyPlanningSceneService : public ServiceCapability<ApplyPlanningSceneService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::ApplyPlanningSceneRequest& request, moveit_msgs::ApplyPlanningSceneResponse& response);
};

}  // namespace sixdof_planning
