#pragma once
// The topics MoveIt's move_group listens to for scene changes (its planning scene monitor): `planning_scene`
// (moveit_msgs/PlanningScene diffs, or full scenes with is_diff false), `collision_object` and
// `attached_collision_object`, in the context's namespace. Each message is applied as apply_planning_scene
// applies a scene; a refused one changes nothing and is reported on move_group/error_reports with its publisher.

#include <string>

#include <moveit_msgs/AttachedCollisionObject.h>
#include <moveit_msgs/CollisionObject.h>
#include <moveit_msgs/PlanningScene.h>
#include <ros/message_event.h>
#include <ros/subscriber.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class PlanningSceneTopics {
 public:
  explicit PlanningSceneTopics(MoveGroupContext* context);

 private:
  void apply(const moveit_msgs::PlanningScene& scene, const std::string& publisher, const std::string& topic);
  void onScene(const ros::MessageEvent<const moveit_msgs::PlanningScene>& event);
  void onCollisionObject(const ros::MessageEvent<const moveit_msgs::CollisionObject>& event);
  void onAttachedCollisionObject(const ros::MessageEvent<const moveit_msgs::AttachedCollisionObject>& event);

  MoveGroupContext* context_;
  ros::Subscriber scene_sub_;
  ros::Subscriber object_sub_;
  ros::Subscriber attached_sub_;
};

}  // namespace sixdof_planning
