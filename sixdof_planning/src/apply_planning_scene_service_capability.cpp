#include "sixdof_planning/apply_planning_scene_service_capability.h"

#include <sixdof_msgs/ApplyPlanningScene.h>

#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

namespace {
const char* const kApplySource = "apply_planning_scene";
}  // namespace

ApplyPlanningSceneService::ApplyPlanningSceneService(MoveGroupContext* context) : context_(context) {
  server_ = context_->nodeHandle().advertiseService("apply_planning_scene", &ApplyPlanningSceneService::handle, this);
}

bool ApplyPlanningSceneService::handle(sixdof_msgs::ApplyPlanningSceneRequest& request,
                                       sixdof_msgs::ApplyPlanningSceneResponse& response) {
  response.error_code = context_->applyScene(request.scene, kApplySource);
  response.success = isSuccess(response.error_code);
  return true;
}

}  // namespace sixdof_planning
