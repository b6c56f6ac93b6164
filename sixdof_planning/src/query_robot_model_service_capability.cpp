#include "sixdof_planning/query_robot_model_service_capability.h"

#include <sixdof_core/mesh_loader.h>
#include <sixdof_core/primitive_dimensions.h>
#include <sixdof_core/robot_model.h>
#include <sixdof_msgs/GetRobotModel.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/errors.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

namespace {
sixdof_msgs::RobotModelJoint toMsg(const sixdof_core::JointModel& joint) {
  sixdof_msgs::RobotModelJoint msg;
  msg.name = joint.name;
  msg.type = sixdof_core::toString(joint.type);
  msg.parent_link = joint.parent_link;
  msg.child_link = joint.child_link;
  msg.origin = eigenToPose(joint.origin);
  msg.axis.x = joint.axis.x();
  msg.axis.y = joint.axis.y();
  msg.axis.z = joint.axis.z();
  msg.continuous = joint.type == sixdof_core::JointType::kContinuous;
  msg.has_position_limits = joint.type != sixdof_core::JointType::kFixed && joint.limits.bounded;
  msg.min_position = joint.limits.lower;
  msg.max_position = joint.limits.upper;
  msg.max_velocity = joint.limits.velocity;
  msg.max_effort = joint.limits.effort;
  msg.variable_index = joint.variable_index;
  if (joint.mimic) {
    msg.mimic_joint = joint.mimic->joint;
    msg.mimic_multiplier = joint.mimic->multiplier;
    msg.mimic_offset = joint.mimic->offset;
  }
  return msg;
}

sixdof_msgs::RobotModelGroup toMsg(const sixdof_core::JointGroup& group) {
  sixdof_msgs::RobotModelGroup msg;
  msg.name = group.name;
  msg.active_joints = group.active_joints;
  msg.joints = group.joints;
  msg.links = group.links;
  msg.subgroups = group.subgroups;
  msg.chain_base_link = group.chain_base;
  msg.chain_tip_link = group.chain_tip;
  return msg;
}

sixdof_msgs::RobotModelGroupState toMsg(const sixdof_core::GroupState& state) {
  sixdof_msgs::RobotModelGroupState msg;
  msg.group = state.group;
  msg.name = state.name;
  for (const auto& [joint, value] : state.values) {
    msg.joint_names.push_back(joint);
    msg.positions.push_back(value);
  }
  return msg;
}

sixdof_msgs::RobotModelEndEffector toMsg(const sixdof_core::EndEffector& eef) {
  sixdof_msgs::RobotModelEndEffector msg;
  msg.name = eef.name;
  msg.parent_link = eef.parent_link;
  msg.group = eef.group;
  msg.parent_group = eef.parent_group;
  return msg;
}

sixdof_msgs::RobotModelGroupState stateMsg(const std::string& group, const GripperState& state) {
  return toMsg(sixdof_core::GroupState{state.name, group, state.positions});
}

geometry_msgs::Vector3 vectorMsg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 msg;
  msg.x = v.x();
  msg.y = v.y();
  msg.z = v.z();
  return msg;
}

// Every item of `items` as its message, appended to `out` in the model's order.
template <class Items, class Msg>
void appendMsgs(const Items& items, std::vector<Msg>* out) {
  for (const auto& item : items) out->push_back(toMsg(item));
}

// A box, sphere or cylinder as a SolidPrimitive (the dimension order is sixdof_core/primitive_dimensions.h's).
shape_msgs::SolidPrimitive primitiveMsg(const sixdof_core::Shape& shape) {
  using Type = sixdof_core::ShapeType;
  shape_msgs::SolidPrimitive msg;
  msg.type = shape.type == Type::kBox      ? shape_msgs::SolidPrimitive::BOX
             : shape.type == Type::kSphere ? shape_msgs::SolidPrimitive::SPHERE
                                           : shape_msgs::SolidPrimitive::CYLINDER;
  msg.dimensions = sixdof_core::primitiveDimensions(shape);
  return msg;
}

shape_msgs::Mesh meshMsg(const sixdof_core::MeshData& mesh) {
  shape_msgs::Mesh msg;
  msg.vertices.resize(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    msg.vertices[i].x = mesh.vertices[i].x();
    msg.vertices[i].y = mesh.vertices[i].y();
    msg.vertices[i].z = mesh.vertices[i].z();
  }
  msg.triangles.resize(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) msg.triangles[i].vertex_indices[k] = static_cast<uint32_t>(mesh.triangles[i][k]);
  }
  return msg;
}
}  // namespace

sixdof_msgs::RobotModelGripper describeGripper(const GraspingConfig& grasping) {
  sixdof_msgs::RobotModelGripper msg;
  msg.group = grasping.group;
  msg.end_effector = grasping.end_effector;
  msg.tcp_frame = grasping.tcp_frame;
  msg.parent_link = grasping.parent_link;
  msg.tcp = eigenToPose(grasping.tcp);
  msg.open = stateMsg(grasping.group, grasping.open);
  msg.closed = stateMsg(grasping.group, grasping.closed);
  msg.max_opening = grasping.max_opening;
  msg.closed_width = grasping.closed_width;
  msg.finger_reach = grasping.finger_reach;
  msg.palm_depth = grasping.palm_depth;
  msg.pad_links = grasping.pad_links;
  msg.closing_direction = vectorMsg(grasping.closing_direction);
  msg.approach_direction = vectorMsg(grasping.approach_direction);
  msg.suction_cup = grasping.suction_cup;
  msg.vacuum_controller = grasping.vacuum_controller;
  msg.max_payload = grasping.max_payload;
  return msg;
}

void describeRobotModel(const sixdof_core::RobotModel& model, sixdof_msgs::GetRobotModelResponse* response) {
  response->robot_name = model.name();
  response->root_link = model.rootLink();
  // MoveIt's model frame: a virtual joint's parent frame names the root link's place in the world.
  response->planning_frame =
      model.virtualJoints().empty() ? model.rootLink() : model.virtualJoints().front().parent_frame;
  for (const auto& link : model.links()) response->link_names.push_back(link.name);
  appendMsgs(model.joints(), &response->joints);
  response->variable_names = model.variableNames();
  appendMsgs(model.groups(), &response->groups);
  appendMsgs(model.groupStates(), &response->group_states);
  appendMsgs(model.endEffectors(), &response->end_effectors);
}

std::string describeCollisionGeometry(const sixdof_core::RobotModel& model,
                                      std::vector<sixdof_msgs::RobotModelLinkGeometry>* geometries) {
  std::vector<sixdof_msgs::RobotModelLinkGeometry> out;
  for (const auto& link : model.collisionGeometry()) {
    sixdof_msgs::RobotModelLinkGeometry msg;
    msg.link_name = link.link_name;
    for (const auto& placed : link.shapes) {
      if (placed.shape.type != sixdof_core::ShapeType::kMesh) {
        msg.primitives.push_back(primitiveMsg(placed.shape));
        msg.primitive_poses.push_back(eigenToPose(placed.origin));
        continue;
      }
      // The loader the collision scene builds the link's FCL mesh with (cached: no second read of the file).
      const auto loaded = sixdof_core::loadMesh(placed.shape.mesh_path, placed.shape.mesh_scale);
      if (!loaded.ok()) return "link '" + link.link_name + "': " + loaded.message;
      msg.meshes.push_back(meshMsg(*loaded.mesh));
      msg.mesh_poses.push_back(eigenToPose(placed.origin));
    }
    out.push_back(std::move(msg));
  }
  *geometries = std::move(out);
  return "";
}

ErrorCode QueryRobotModelService::handle(const sixdof_msgs::GetRobotModelRequest& request,
                                    sixdof_msgs::GetRobotModelResponse& response) {
  describeRobotModel(*context_->model(), &response);
  if (context_->config().grasping) response.grippers.push_back(describeGripper(*context_->config().grasping));
  ErrorCode code = makeSuccess(service_);
  if (request.include_collision_geometry) {
    const std::string error = describeCollisionGeometry(*context_->model(), &response.link_geometries);
    if (!error.empty()) code = makeError(ErrorCode::FAILURE, "collision geometry: " + error, service_);
  }
  response.error_message = code.message;
  return answer(code, &response);
}

template class ServiceCapability<QueryRobotModelService>;

}  // namespace sixdof_planning
