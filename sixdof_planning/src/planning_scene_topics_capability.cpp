#include "sixdof_planning/planning_scene_topics_capability.h"

#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

PlanningSceneTopics::PlanningSceneTopics(MoveGroupContext* context) : context_(context) {
  ros::NodeHandle& nh = context_->nodeHandle();
  // Every message counts (a scene built object by object): generous queues.
  scene_sub_ = nh.subscribe("planning_scene", 100, &PlanningSceneTopics::onScene, this);
  object_sub_ = nh.subscribe("collision_object", 100, &PlanningSceneTopics::onCollisionObject, this);
  attached_sub_ = nh.subscribe("attached_collision_object", 100, &PlanningSceneTopics::onAttachedCollisionObject, this);
}

void PlanningSceneTopics::apply(const moveit_msgs::PlanningScene& scene, const std::string& publisher,
                                const std::string& topic) {
  const std::string resolved = context_->nodeHandle().resolveName(topic);
  const ErrorCode code = context_->applyScene(scene, resolved);
  if (!isSuccess(code)) context_->reportError(publisher, resolved, code);
}

void PlanningSceneTopics::onScene(const ros::MessageEvent<const moveit_msgs::PlanningScene>& event) {
  apply(*event.getConstMessage(), event.getPublisherName(), "planning_scene");
}

void PlanningSceneTopics::onCollisionObject(const ros::MessageEvent<const moveit_msgs::CollisionObject>& event) {
  moveit_msgs::PlanningScene diff;
  diff.is_diff = true;
  diff.robot_state.is_diff = true;
  diff.world.collision_objects.push_back(*event.getConstMessage());
  apply(diff, event.getPublisherName(), "collision_object");
}

void PlanningSceneTopics::onAttachedCollisionObject(
    const ros::MessageEvent<const moveit_msgs::AttachedCollisionObject>& event) {
  moveit_msgs::PlanningScene diff;
  diff.is_diff = true;
  diff.robot_state.is_diff = true;
  diff.robot_state.attached_collision_objects.push_back(*event.getConstMessage());
  apply(diff, event.getPublisherName(), "attached_collision_object");
}

}  // namespace sixdof_planning
