#include "sixdof_planning/get_planning_scene_service_capability.h"

#include <moveit_msgs/GetPlanningScene.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

ErrorCode GetPlanningSceneService::handle(const moveit_msgs::GetPlanningSceneRequest& request,
                                          moveit_msgs::GetPlanningSceneResponse& response) {
  response.scene = context_->sceneMessage(request.components.components, service_);
  return makeSuccess(service_);
}

template class ServiceCapability<GetPlanningSceneService>;

}  // namespace sixdof_planning
