#include "sixdof_planning/state_validation_service_capability.h"

#include <moveit_msgs/GetStateValidity.h>
#include <tf2_eigen/tf2_eigen.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/constraints.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {
uint32_t bodyType(sixdof_core::BodyType type) {
  switch (type) {
    case sixdof_core::BodyType::kRobotLink:
      return moveit_msgs::ContactInformation::ROBOT_LINK;
    case sixdof_core::BodyType::kAttachedObject:
      return moveit_msgs::ContactInformation::ROBOT_ATTACHED;
    case sixdof_core::BodyType::kWorldObject:
      break;
  }
  return moveit_msgs::ContactInformation::WORLD_OBJECT;
}
}  // namespace

ErrorCode StateValidityService::handle(const moveit_msgs::GetStateValidityRequest& request,
                                       moveit_msgs::GetStateValidityResponse& response) {
  // moveit_msgs' answer has no error code: a request that cannot be checked answers valid = false, and its code and
  // words go to move_group/error_reports.
  response.valid = false;
  if (!request.group_name.empty()) {
    const ErrorCode code = validateGroup(*context_->model(), request.group_name, service_);
    if (!isSuccess(code)) return code;
  }
  sixdof_core::RobotState state(context_->model());
  std::shared_ptr<const SceneStore> scene;
  ErrorCode code = context_->resolveRobotState(request.robot_state, "robot_state", service_, &state, &scene);
  if (!isSuccess(code)) return code;
  code = evaluateConstraints(state, request.constraints, "constraints", service_, &response.constraint_result);
  if (!isSuccess(code)) return code;
  const auto report = checkStateCollision(state, *scene->collision());
  for (const auto& contact : report.contacts) {
    moveit_msgs::ContactInformation info;
    info.header.frame_id = context_->planningFrame();
    info.header.stamp = ros::Time::now();
    info.position = tf2::toMsg(contact.position);
    tf2::toMsg(contact.normal, info.normal);
    info.depth = contact.depth;
    info.contact_body_1 = contact.body1;
    info.contact_body_2 = contact.body2;
    info.body_type_1 = bodyType(contact.type1);
    info.body_type_2 = bodyType(contact.type2);
    response.contacts.push_back(info);
  }
  // A measured state reads a hair past a limit (a closed finger at -2e-8 m): within start_state_max_bounds_error it
  // is on the limit, as for planning.
  const std::string bounds = boundsViolation(state, context_->config().start_state_max_bounds_error);
  if (!bounds.empty()) ROS_DEBUG_STREAM(service_ << ": state not valid: " << bounds);
  bool constraints_met = true;
  for (const auto& result : response.constraint_result) constraints_met = constraints_met && result.result;
  response.valid = !report.colliding && bounds.empty() && constraints_met;
  return makeSuccess(service_);
}

template class ServiceCapability<StateValidityService>;

}  // namespace sixdof_planning
