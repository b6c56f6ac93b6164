#include "sixdof_planning/apply_planning_scene_service_capability.h"

#include <moveit_msgs/ApplyPlanningScene.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

ErrorCode ApplyPlanningSceneService::handle(const moveit_msgs::ApplyPlanningSceneRequest& request,
                                       moveit_msgs::ApplyPlanningSceneResponse& response) {
  // moveit_msgs' answer is success alone: the code and words of a refusal go to move_group/error_reports.
  const ErrorCode code = context_->applyScene(request.scene, service_);
  response.success = isSuccess(code);
  return code;
}

template class ServiceCapability<ApplyPlanningSceneService>;

}  // namespace sixdof_planning
