#pragma once
// get_planning_scene (MoveIt's get_planning_scene_service_capability): the whole current scene.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class GetPlanningSceneService : public ServiceCapability<GetPlanningSceneService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const moveit_msgs::GetPlanningSceneRequest& request, moveit_msgs::GetPlanningSceneResponse& response);
};

}  // namespace sixdof_planning
