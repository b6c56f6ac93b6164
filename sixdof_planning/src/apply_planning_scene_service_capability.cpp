#include "sixdof_planning/apply_planning_scene_service_capability.h"

#include <sixdof_msgs/ApplyPlanningScene.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

bool ApplyPlanningSceneService::handle(sixdof_msgs::ApplyPlanningSceneRequest& request,
                                       sixdof_msgs::ApplyPlanningSceneResponse& response) {
  response.error_code = context_->applyScene(request.scene, service_);
  response.success = isSuccess(response.error_code);
  return true;
}

template class ServiceCapability<ApplyPlanningSceneService>;

}  // namespace sixdof_planning
