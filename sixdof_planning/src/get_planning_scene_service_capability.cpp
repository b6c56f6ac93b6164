#include "sixdof_planning/get_planning_scene_service_capability.h"

#include <sixdof_msgs/GetPlanningScene.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {


bool GetPlanningSceneService::handle(sixdof_msgs::GetPlanningSceneRequest&,
                                     sixdof_msgs::GetPlanningSceneResponse& response) {
  const auto scene = context_->scene();
  response.scene.name = "move_group";
  response.scene.robot_model_name = context_->model()->name();
  response.scene.is_diff = false;
  sixdof_core::RobotState state(context_->model());
  // The scene has objects even before joint_states arrive; the joint values are then left empty.
  if (isSuccess(context_->currentState(service_, &state))) {
    response.scene.robot_state.joint_state = toJointState(state);
  }
  response.scene.robot_state.attached_collision_objects = scene->attachedObjects();
  response.scene.world.collision_objects = scene->worldObjects();
  return true;
}

template class ServiceCapability<GetPlanningSceneService>;

}  // namespace sixdof_planning
