#include "sixdof_planning/query_robot_model_service_capability.h"

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
}  // namespace

void describeRobotModel(const sixdof_core::RobotModel& model, sixdof_msgs::GetRobotModelResponse* response) {
  response->robot_name = model.name();
  response->root_link = model.rootLink();
  // MoveIt's model frame: a virtual joint's parent frame names the root link's place in the world.
  response->planning_frame =
      model.virtualJoints().empty() ? model.rootLink() : model.virtualJoints().front().parent_frame;
  for (const auto& link : model.links()) response->link_names.push_back(link.name);
  for (const auto& joint : model.joints()) response->joints.push_back(toMsg(joint));
  response->variable_names = model.variableNames();
  for (const auto& group : model.groups()) {
    sixdof_msgs::RobotModelGroup msg;
    msg.name = group.name;
    msg.active_joints = group.active_joints;
    msg.joints = group.joints;
    msg.links = group.links;
    msg.subgroups = group.subgroups;
    msg.chain_base_link = group.chain_base;
    msg.chain_tip_link = group.chain_tip;
    response->groups.push_back(msg);
  }
  for (const auto& state : model.groupStates()) {
    sixdof_msgs::RobotModelGroupState msg;
    msg.group = state.group;
    msg.name = state.name;
    for (const auto& [joint, value] : state.values) {
      msg.joint_names.push_back(joint);
      msg.positions.push_back(value);
    }
    response->group_states.push_back(msg);
  }
  for (const auto& eef : model.endEffectors()) {
    sixdof_msgs::RobotModelEndEffector msg;
    msg.name = eef.name;
    msg.parent_link = eef.parent_link;
    msg.group = eef.group;
    msg.parent_group = eef.parent_group;
    response->end_effectors.push_back(msg);
  }
}

bool QueryRobotModelService::handle(sixdof_msgs::GetRobotModelRequest& /*request*/,
                                    sixdof_msgs::GetRobotModelResponse& response) {
  describeRobotModel(*context_->model(), &response);
  response.error_code = makeSuccess(service_);
  return true;
}

template class ServiceCapability<QueryRobotModelService>;

}  // namespace sixdof_planning
