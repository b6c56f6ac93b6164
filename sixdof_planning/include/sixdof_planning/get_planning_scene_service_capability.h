#pragma once
// get_planning_scene (MoveIt's get_planning_scene_service_capability): the whole current scene.

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class GetPlanningSceneService : public ServiceCapability<GetPlanningSceneService> {
 public:
  using ServiceCapability::ServiceCapability;
  bool handle(sixdof_msgs::GetPlanningSceneRequest& request, sixdof_msgs::GetPlanningSceneResponse& response);
};

}  // namespace sixdof_planning
