#include "sixdof_planning/scene_store.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include <sixdof_core/primitive_dimensions.h>

#include "sixdof_planning/conversions.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {

using moveit_msgs::CollisionObject;

// The core loads meshes from files (and caches them by path): a message mesh becomes an OBJ file named
// after its content, in a per-process directory.
std::string writeMeshFile(const shape_msgs::Mesh& mesh) {
  std::ostringstream obj;
  obj.precision(17);
  for (const auto& v : mesh.vertices) obj << "v " << v.x << " " << v.y << " " << v.z << "\n";
  for (const auto& t : mesh.triangles) {
    obj << "f " << t.vertex_indices[0] + 1 << " " << t.vertex_indices[1] + 1 << " " << t.vertex_indices[2] + 1 << "\n";
  }
  const std::string text = obj.str();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sixdof_planning_meshes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / (std::to_string(std::hash<std::string>()(text)) + ".obj");
  if (!std::filesystem::exists(path)) {
    std::ofstream out(path);
    out << text;
  }
  return path.string();
}

std::string planningFrame(const sixdof_core::RobotModel& model) { return model.rootLink(); }

}  // namespace

SceneStore::SceneStore(sixdof_core::RobotModelConstPtr model, double link_padding) : model_(std::move(model)) {
  const auto geometry = model_->collisionGeometry();
  std::set<std::string> with_geometry;
  for (const auto& link : geometry) with_geometry.insert(link.link_name);
  // SRDF pairs may name links without collision geometry (Adjacent through geometry-less links); those
  // never collide anyway.
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const auto& pair : model_->disabledCollisionPairs()) {
    if (with_geometry.count(pair.link1) && with_geometry.count(pair.link2)) pairs.emplace_back(pair.link1, pair.link2);
  }
  sixdof_core::CollisionSceneOptions options;
  options.link_padding = link_padding;
  collision_ = std::make_shared<sixdof_core::CollisionScene>(geometry, pairs, options);
}

SceneStore::SceneStore(const SceneStore& other)
    : model_(other.model_),
      collision_(std::make_shared<sixdof_core::CollisionScene>(*other.collision_)),
      world_(other.world_),
      attached_(other.attached_),
      colors_(other.colors_),
      occupancy_map_(other.occupancy_map_),
      occupancy_map_pose_(other.occupancy_map_pose_) {}

void SceneStore::setOccupancyMap(std::shared_ptr<const sixdof_core::OccupancyMap> map,
                                 const Eigen::Isometry3d& map_pose) {
  occupancy_map_ = map;
  occupancy_map_pose_ = map_pose;
  collision_->setOccupancyMap(std::move(map), map_pose);
}

void SceneStore::octomapMessage(octomap_msgs::OctomapWithPose* msg) const {
  if (!occupancy_map_) return;
  msg->header.frame_id = planningFrame(*model_);
  msg->origin = eigenToPose(occupancy_map_pose_);
  msg->octomap.header.frame_id = planningFrame(*model_);
  msg->octomap.binary = true;
  msg->octomap.id = "OcTree";
  msg->octomap.resolution = occupancy_map_->resolution();
  const std::string data = occupancy_map_->binaryData();
  msg->octomap.data.assign(data.begin(), data.end());
}

moveit_msgs::AllowedCollisionMatrix SceneStore::allowedCollisionMatrix() const {
  moveit_msgs::AllowedCollisionMatrix acm;
  acm.entry_names = collision_->linkNames();
  const size_t n = acm.entry_names.size();
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < n; ++i) index[acm.entry_names[i]] = i;
  acm.entry_values.resize(n);
  for (size_t i = 0; i < n; ++i) {
    acm.entry_values[i].enabled.assign(n, false);
    acm.entry_values[i].enabled[i] = true;
  }
  for (const auto& pair : model_->disabledCollisionPairs()) {
    auto a = index.find(pair.link1);
    auto b = index.find(pair.link2);
    if (a == index.end() || b == index.end()) continue;
    acm.entry_values[a->second].enabled[b->second] = true;
    acm.entry_values[b->second].enabled[a->second] = true;
  }
  return acm;
}

std::vector<moveit_msgs::ObjectColor> SceneStore::objectColors() const {
  std::vector<moveit_msgs::ObjectColor> result;
  for (const auto& entry : colors_) {
    if (!world_.count(entry.first) && !attached_.count(entry.first)) continue;
    moveit_msgs::ObjectColor color;
    color.id = entry.first;
    color.color = entry.second;
    result.push_back(color);
  }
  return result;
}

void SceneStore::clearAttachedObjects() {
  for (const auto& entry : attached_) collision_->removeAttachedObject(entry.first);
  attached_.clear();
}

ErrorCode SceneStore::frameTransform(const sixdof_core::RobotState& state, const std::string& frame,
                                     const std::string& source, Eigen::Isometry3d* frame_pose) {
  const auto& model = state.model();
  if (frame.empty() || frame == model.rootLink()) {
    *frame_pose = Eigen::Isometry3d::Identity();
    return makeSuccess(source);
  }
  for (const auto& joint : model.virtualJoints()) {
    if (joint.type == "fixed" && joint.parent_frame == frame && joint.child_link == model.rootLink()) {
      *frame_pose = Eigen::Isometry3d::Identity();
      return makeSuccess(source);
    }
  }
  if (model.linkIndex(frame) >= 0) {
    *frame_pose = state.linkTransform(frame);
    return makeSuccess(source);
  }
  return makeError(ErrorCode::FRAME_TRANSFORM_FAILURE,
                   "unknown frame '" + frame + "' (use the planning frame '" + model.rootLink() +
                       "', its fixed parent frame or a robot link)",
                   source);
}

ErrorCode SceneStore::sceneError(const sixdof_core::SceneStatus& status, const std::string& source) const {
  using Code = sixdof_core::SceneStatusCode;
  switch (status.status) {
    case Code::kOk:
      return makeSuccess(source);
    case Code::kUnknownName:
    case Code::kDuplicateName:
      return makeError(ErrorCode::INVALID_OBJECT_NAME, status.message, source);
    default:
      return makeError(ErrorCode::FAILURE, status.message, source);
  }
}

ErrorCode SceneStore::toShapes(const CollisionObject& object, const std::string& source,
                               std::vector<sixdof_core::PlacedShape>* shapes) const {
  for (size_t i = 0; i < object.primitives.size(); ++i) {
    const auto& primitive = object.primitives[i];
    sixdof_core::PlacedShape placed;
    placed.origin = poseToEigen(object.primitive_poses[i]);
    // validateCollisionObject has checked the type and the number of dimensions.
    const std::optional<sixdof_core::ShapeType> type = primitiveType(primitive.type);
    const std::optional<sixdof_core::Shape> shape =
        type ? sixdof_core::primitiveShape(*type, primitive.dimensions) : std::nullopt;
    if (!shape) {
      return makeError(ErrorCode::FAILURE,
                       "primitive " + std::to_string(i) + " of '" + object.id + "' is not a valid primitive", source);
    }
    placed.shape = *shape;
    shapes->push_back(placed);
  }
  for (size_t i = 0; i < object.meshes.size(); ++i) {
    sixdof_core::PlacedShape placed;
    placed.origin = poseToEigen(object.mesh_poses[i]);
    placed.shape.type = sixdof_core::Shape::Type::kMesh;
    try {
      placed.shape.mesh_path = writeMeshFile(object.meshes[i]);
    } catch (const std::exception& e) {
      return makeError(ErrorCode::FAILURE,
                       "cannot store mesh " + std::to_string(i) + " of '" + object.id + "': " + e.what(), source);
    }
    shapes->push_back(placed);
  }
  return makeSuccess(source);
}

ErrorCode SceneStore::applyCollisionObject(const CollisionObject& object, const sixdof_core::RobotState& state,
                                           const std::string& source) {
  ErrorCode code = validateCollisionObject(object, "collision object", source);
  if (!isSuccess(code)) return code;
  const bool exists = world_.count(object.id) > 0;
  if (object.operation == CollisionObject::REMOVE) {
    if (object.id.empty()) {
      collision_->clearWorld();
      world_.clear();
      return makeSuccess(source);
    }
    if (!exists) {
      return makeError(ErrorCode::INVALID_OBJECT_NAME,
                       "cannot remove '" + object.id + "': no such world object" +
                           (attached_.count(object.id) ? " (it is attached: detach it first)" : ""),
                       source);
    }
    return removeWorldObject(object.id, source);
  }
  Eigen::Isometry3d frame_pose;
  code = frameTransform(state, object.header.frame_id, source, &frame_pose);
  if (!isSuccess(code)) return code;
  const Eigen::Isometry3d pose = frame_pose * poseToEigen(object.pose);
  if (object.operation == CollisionObject::MOVE) {
    if (!exists) {
      return makeError(ErrorCode::INVALID_OBJECT_NAME, "cannot move '" + object.id + "': no such world object",
                       source);
    }
    code = sceneError(collision_->moveWorldObject(object.id, pose), source);
    if (isSuccess(code)) world_[object.id].pose = eigenToPose(pose);
    return code;
  }
  CollisionObject stored = object;
  stored.header.frame_id = planningFrame(*model_);
  stored.header.stamp = ros::Time();
  stored.pose = eigenToPose(pose);
  stored.operation = CollisionObject::ADD;
  if (object.operation == CollisionObject::APPEND && exists) {
    // The new shapes join the existing object: re-express their poses in its frame.
    const CollisionObject& old = world_.at(object.id);
    const Eigen::Isometry3d to_old = poseToEigen(old.pose).inverse() * pose;
    stored = old;
    for (size_t i = 0; i < object.primitives.size(); ++i) {
      stored.primitives.push_back(object.primitives[i]);
      stored.primitive_poses.push_back(eigenToPose(to_old * poseToEigen(object.primitive_poses[i])));
    }
    for (size_t i = 0; i < object.meshes.size(); ++i) {
      stored.meshes.push_back(object.meshes[i]);
      stored.mesh_poses.push_back(eigenToPose(to_old * poseToEigen(object.mesh_poses[i])));
    }
  }
  sixdof_core::WorldObject world_object;
  world_object.id = stored.id;
  world_object.pose = poseToEigen(stored.pose);
  code = toShapes(stored, source, &world_object.shapes);
  if (!isSuccess(code)) return code;
  // ADD replaces an object of the same id, as in MoveIt.
  if (exists) {
    code = removeWorldObject(object.id, source);
    if (!isSuccess(code)) return code;
  }
  code = sceneError(collision_->addWorldObject(world_object), source);
  if (isSuccess(code)) world_[stored.id] = stored;
  return code;
}

ErrorCode SceneStore::removeWorldObject(const std::string& id, const std::string& source) {
  const ErrorCode code = sceneError(collision_->removeWorldObject(id), source);
  if (isSuccess(code)) world_.erase(id);
  return code;
}

ErrorCode SceneStore::removeAttachedObject(const std::string& id, const std::string& source) {
  const ErrorCode code = sceneError(collision_->removeAttachedObject(id), source);
  if (isSuccess(code)) attached_.erase(id);
  return code;
}

ErrorCode SceneStore::carrierLink(const std::string& link, const std::string& source, std::string* carrier,
                                  Eigen::Isometry3d* link_in_carrier) const {
  // Objects may be attached to any link, but the collision scene only has links with geometry: a link
  // without geometry (e.g. tcp) hands its objects to the nearest ancestor it is rigidly fixed to.
  *carrier = link;
  *link_in_carrier = Eigen::Isometry3d::Identity();
  while (collision_->linkIndex(*carrier) < 0) {
    const auto& link_model = model_->link(*carrier);
    if (link_model.parent_joint < 0 ||
        model_->joints()[link_model.parent_joint].type != sixdof_core::JointType::kFixed) {
      return makeError(ErrorCode::INVALID_LINK_NAME,
                       "link '" + link + "' has no collision geometry and is not rigidly fixed to a link that has",
                       source);
    }
    *link_in_carrier = model_->joints()[link_model.parent_joint].origin * *link_in_carrier;
    *carrier = model_->links()[link_model.parent_link].name;
  }
  return makeSuccess(source);
}

ErrorCode SceneStore::detach(const std::string& id, const sixdof_core::RobotState& state, const std::string& source) {
  const auto& attached = attached_.at(id);
  const Eigen::Isometry3d link_pose = state.linkTransform(attached.link_name);
  std::string carrier;
  Eigen::Isometry3d link_in_carrier;
  ErrorCode code = carrierLink(attached.link_name, source, &carrier, &link_in_carrier);
  if (!isSuccess(code)) return code;
  code = sceneError(collision_->detachObject(id, state.linkTransform(carrier)), source);
  if (!isSuccess(code)) return code;
  CollisionObject object = attached.object;
  object.header.frame_id = planningFrame(*model_);
  object.pose = eigenToPose(link_pose * poseToEigen(attached.object.pose));
  object.operation = CollisionObject::ADD;
  world_[id] = object;
  attached_.erase(id);
  return makeSuccess(source);
}

ErrorCode SceneStore::applyAttachedObject(const moveit_msgs::AttachedCollisionObject& attached,
                                          const sixdof_core::RobotState& state, const std::string& source) {
  const CollisionObject& object = attached.object;
  ErrorCode code = validateCollisionObject(object, "attached object", source, false);
  if (!isSuccess(code)) return code;
  if (object.operation == CollisionObject::REMOVE) {
    if (object.id.empty()) {
      std::vector<std::string> ids;
      for (const auto& entry : attached_) ids.push_back(entry.first);
      for (const auto& id : ids) {
        code = detach(id, state, source);
        if (!isSuccess(code)) return code;
      }
      return makeSuccess(source);
    }
    if (!attached_.count(object.id)) {
      return makeError(ErrorCode::INVALID_OBJECT_NAME, "cannot detach '" + object.id + "': it is not attached", source);
    }
    return detach(object.id, state, source);
  }
  if (object.operation != CollisionObject::ADD) {
    return makeError(ErrorCode::FAILURE,
                     "attached object '" + object.id + "': only ADD (attach) and REMOVE (detach) are supported",
                     source);
  }
  code = validateLink(*model_, attached.link_name, source);
  if (!isSuccess(code)) {
    code.message = "attached object '" + object.id + "': " + code.message;
    return code;
  }
  for (const auto& link : attached.touch_links) {
    code = validateLink(*model_, link, source);
    if (!isSuccess(code)) {
      code.message = "attached object '" + object.id + "' touch_links: " + code.message;
      return code;
    }
  }
  // Touch links without collision geometry (e.g. a tcp frame) cannot touch anything; the collision scene
  // only knows links with geometry.
  std::vector<std::string> touch_links;
  for (const auto& link : attached.touch_links) {
    if (collision_->linkIndex(link) >= 0) touch_links.push_back(link);
  }
  std::string carrier;
  Eigen::Isometry3d link_in_carrier;
  code = carrierLink(attached.link_name, source, &carrier, &link_in_carrier);
  if (!isSuccess(code)) return code;
  const Eigen::Isometry3d link_pose = state.linkTransform(attached.link_name);
  moveit_msgs::AttachedCollisionObject stored = attached;
  stored.object.header.frame_id = attached.link_name;
  stored.object.header.stamp = ros::Time();
  stored.object.operation = CollisionObject::ADD;
  if (object.primitives.empty() && object.meshes.empty()) {
    // Attach an existing world object where it is.
    auto it = world_.find(object.id);
    if (it == world_.end()) {
      return makeError(ErrorCode::INVALID_OBJECT_NAME,
                       "cannot attach '" + object.id + "': no such world object (give shapes to attach a new object)",
                       source);
    }
    code = sceneError(collision_->attachWorldObject(object.id, carrier, state.linkTransform(carrier), touch_links),
                      source);
    if (!isSuccess(code)) return code;
    const CollisionObject world_object = it->second;
    stored.object.primitives = world_object.primitives;
    stored.object.primitive_poses = world_object.primitive_poses;
    stored.object.meshes = world_object.meshes;
    stored.object.mesh_poses = world_object.mesh_poses;
    stored.object.pose = eigenToPose(link_pose.inverse() * poseToEigen(world_object.pose));
    world_.erase(it);
    attached_[object.id] = stored;
    return makeSuccess(source);
  }
  Eigen::Isometry3d frame_pose;
  code = frameTransform(state, object.header.frame_id, source, &frame_pose);
  if (!isSuccess(code)) return code;
  stored.object.pose = eigenToPose(link_pose.inverse() * frame_pose * poseToEigen(object.pose));
  sixdof_core::AttachedObject core_object;
  core_object.id = object.id;
  core_object.link_name = carrier;
  core_object.pose_in_link = link_in_carrier * poseToEigen(stored.object.pose);
  core_object.touch_links = touch_links;
  code = toShapes(object, source, &core_object.shapes);
  if (!isSuccess(code)) return code;
  // A new attached object replaces a world or attached object of the same id, as in MoveIt.
  if (world_.count(object.id)) {
    code = removeWorldObject(object.id, source);
    if (!isSuccess(code)) return code;
  }
  if (attached_.count(object.id)) {
    code = removeAttachedObject(object.id, source);
    if (!isSuccess(code)) return code;
  }
  code = sceneError(collision_->attachObject(core_object), source);
  if (isSuccess(code)) attached_[object.id] = stored;
  return code;
}

ErrorCode SceneStore::apply(const moveit_msgs::PlanningScene& scene, const sixdof_core::RobotState& state,
                            const std::string& source) {
  if (!scene.robot_state.joint_state.name.empty() || !scene.robot_state.multi_dof_joint_state.joint_names.empty()) {
    return makeError(ErrorCode::FAILURE,
                     "scene.robot_state sets joints (" + joinNames(scene.robot_state.joint_state.name) +
                         joinNames(scene.robot_state.multi_dof_joint_state.joint_names) +
                         "): the planning scene follows joint_states, its joint values cannot be set",
                     source);
  }
  const auto refuse = [&](const std::string& field, const std::string& why) {
    return makeError(ErrorCode::FAILURE, "scene." + field + " is not supported: " + why, source);
  };
  if (!scene.fixed_frame_transforms.empty()) {
    return refuse("fixed_frame_transforms", "the scene's frames are the planning frame and the robot's links");
  }
  const auto& acm = scene.allowed_collision_matrix;
  if (!acm.entry_names.empty() || !acm.entry_values.empty() || !acm.default_entry_names.empty() ||
      !acm.default_entry_values.empty()) {
    return refuse("allowed_collision_matrix",
                  "allowed collisions come from the SRDF's disable_collisions and attached objects' touch_links");
  }
  if (!scene.link_padding.empty()) return refuse("link_padding", "use robot_description_planning/default_robot_padding");
  if (!scene.link_scale.empty()) return refuse("link_scale", "links are checked at their URDF size");
  if (!scene.world.octomap.octomap.data.empty()) {
    return refuse("world.octomap", "the occupancy map is built by move_group's sensors (sensors_3d.yaml)");
  }
  for (size_t i = 0; i < scene.object_colors.size(); ++i) {
    if (scene.object_colors[i].id.empty()) {
      return makeError(ErrorCode::INVALID_OBJECT_NAME, "scene.object_colors[" + std::to_string(i) + "] has an empty id",
                       source);
    }
  }
  if (!scene.is_diff) {
    clearAttachedObjects();
    collision_->clearWorld();
    world_.clear();
    colors_.clear();
  }
  for (size_t i = 0; i < scene.world.collision_objects.size(); ++i) {
    ErrorCode code = applyCollisionObject(scene.world.collision_objects[i], state, source);
    if (!isSuccess(code)) {
      code.message = "world.collision_objects[" + std::to_string(i) + "]: " + code.message;
      return code;
    }
  }
  for (size_t i = 0; i < scene.robot_state.attached_collision_objects.size(); ++i) {
    ErrorCode code = applyAttachedObject(scene.robot_state.attached_collision_objects[i], state, source);
    if (!isSuccess(code)) {
      code.message = "robot_state.attached_collision_objects[" + std::to_string(i) + "]: " + code.message;
      return code;
    }
  }
  for (const auto& color : scene.object_colors) colors_[color.id] = color.color;
  return makeSuccess(source);
}

std::vector<CollisionObject> SceneStore::worldObjects() const {
  std::vector<CollisionObject> result;
  for (const auto& entry : world_) result.push_back(entry.second);
  return result;
}

std::vector<moveit_msgs::AttachedCollisionObject> SceneStore::attachedObjects() const {
  std::vector<moveit_msgs::AttachedCollisionObject> result;
  for (const auto& entry : attached_) result.push_back(entry.second);
  return result;
}

}  // namespace sixdof_planning
