#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <visualization_msgs/MarkerArray.h>

#include <moveit_msgs/AllowedCollisionMatrix.h>
#include <moveit_msgs/AttachedCollisionObject.h>
#include <moveit_msgs/CollisionObject.h>
#include <moveit_msgs/ObjectColor.h>
#include <moveit_msgs/PlanningScene.h>
#include <octomap_msgs/OctomapWithPose.h>
#include <sixdof_core/collision.h>
#include <sixdof_core/occupancy_map.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_planning/errors.h"

namespace sixdof_planning {

// The planning scene's objects: the core's CollisionScene plus the messages that describe its world and
// attached objects (what get_planning_scene returns and the markers show). World object messages are kept in
// the planning frame, attached ones in their link's frame.
//
// A store is a value: copies are deep, so a request can apply a diff to a copy while others keep using
// the original, and the node swaps in a modified copy (copy-on-write).
class SceneStore {
 public:
  // link_padding (m, >= 0): every robot link's collision geometry grows by it (MoveIt's default_robot_padding).
  explicit SceneStore(sixdof_core::RobotModelConstPtr model, double link_padding = 0.0);
  SceneStore(const SceneStore& other);
  SceneStore& operator=(const SceneStore&) = delete;

  const sixdof_core::RobotModel& model() const { return *model_; }
  std::shared_ptr<const sixdof_core::CollisionScene> collision() const { return collision_; }

  // Applies a PlanningScene message (a diff, or with is_diff false a full replacement of the objects and colours)
  // at the robot state `state` (which places attached objects and resolves link frames). The robot_state's joint
  // values are not part of the scene (the node follows joint_states), so setting them is an error, as are the
  // parts sixdof does not support (fixed frame transforms, an allowed collision matrix, link padding or scale,
  // an octomap): each is refused with FAILURE naming the field. Object colours are kept.
  // On error the store may be partly modified: apply to a copy and keep it only on success.
  ErrorCode apply(const moveit_msgs::PlanningScene& scene, const sixdof_core::RobotState& state,
                  const std::string& source);
  ErrorCode applyCollisionObject(const moveit_msgs::CollisionObject& object, const sixdof_core::RobotState& state,
                                 const std::string& source);
  ErrorCode applyAttachedObject(const moveit_msgs::AttachedCollisionObject& attached,
                                const sixdof_core::RobotState& state, const std::string& source);

  // Removes every attached object from the robot (a full robot state in a request replaces them).
  void clearAttachedObjects();

  // The occupancy map robot links and attached objects collide against (see CollisionScene::setOccupancyMap);
  // copies of the store share it.
  void setOccupancyMap(std::shared_ptr<const sixdof_core::OccupancyMap> map, const Eigen::Isometry3d& map_pose);
  // The map as octomap_msgs carries it (binary OcTree in the planning frame); left empty without a map.
  void octomapMessage(octomap_msgs::OctomapWithPose* msg) const;
  // The SRDF's allowed collisions between the links with collision geometry (MoveIt's ACM, no default entries).
  moveit_msgs::AllowedCollisionMatrix allowedCollisionMatrix() const;
  // Colours set through object_colors, of objects still in the scene.
  std::vector<moveit_msgs::ObjectColor> objectColors() const;

  // World and attached objects as messages (ADD operations).
  std::vector<moveit_msgs::CollisionObject> worldObjects() const;
  std::vector<moveit_msgs::AttachedCollisionObject> attachedObjects() const;
  // Markers of every object (world objects in the planning frame, attached ones in their link frame),
  // preceded by a DELETEALL marker so removed objects disappear.
  visualization_msgs::MarkerArray markers() const;

  // Pose in the planning frame of `frame` (the planning frame, the virtual joint's parent frame, or a link).
  static ErrorCode frameTransform(const sixdof_core::RobotState& state, const std::string& frame,
                                  const std::string& source, Eigen::Isometry3d* frame_pose);

 private:
  // Shapes of a validated message.
  ErrorCode toShapes(const moveit_msgs::CollisionObject& object, const std::string& source,
                     std::vector<sixdof_core::PlacedShape>* shapes) const;
  ErrorCode sceneError(const sixdof_core::SceneStatus& status, const std::string& source) const;
  // The link with collision geometry that carries objects attached to `link`, and `link`'s pose in it.
  ErrorCode carrierLink(const std::string& link, const std::string& source, std::string* carrier,
                        Eigen::Isometry3d* link_in_carrier) const;
  ErrorCode detach(const std::string& id, const sixdof_core::RobotState& state, const std::string& source);
  // Remove a world (attached) object from the collision scene and, if that succeeded, from the stored messages.
  ErrorCode removeWorldObject(const std::string& id, const std::string& source);
  ErrorCode removeAttachedObject(const std::string& id, const std::string& source);

  sixdof_core::RobotModelConstPtr model_;
  std::shared_ptr<sixdof_core::CollisionScene> collision_;
  std::map<std::string, moveit_msgs::CollisionObject> world_;
  std::map<std::string, moveit_msgs::AttachedCollisionObject> attached_;
  std::map<std::string, std_msgs::ColorRGBA> colors_;
  std::shared_ptr<const sixdof_core::OccupancyMap> occupancy_map_;
  Eigen::Isometry3d occupancy_map_pose_ = Eigen::Isometry3d::Identity();
};

}  // namespace sixdof_planning
