#include "sixdof_planning/state_validation_service_capability.h"

#include <sixdof_msgs/GetStateValidity.h>
#include <tf2_eigen/tf2_eigen.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {
uint32_t bodyType(sixdof_core::BodyType type) {
  switch (type) {
    case sixdof_core::BodyType::kRobotLink:
      return sixdof_msgs::ContactInformation::ROBOT_LINK;
    case sixdof_core::BodyType::kAttachedObject:
      return sixdof_msgs::ContactInformation::ROBOT_ATTACHED;
    case sixdof_core::BodyType::kWorldObject:
      break;
  }
  return sixdof_msgs::ContactInformation::WORLD_OBJECT;
}
}  // namespace

bool StateValidityService::handle(sixdof_msgs::GetStateValidityRequest& request,
                                  sixdof_msgs::GetStateValidityResponse& response) {
  ErrorCode& code = response.error_code;
  response.valid = false;
  if (!request.group_name.empty()) {
    code = validateGroup(*context_->model(), request.group_name, service_);
    if (!isSuccess(code)) return true;
  }
  sixdof_core::RobotState state(context_->model());
  std::shared_ptr<const SceneStore> scene;
  code = context_->resolveRobotState(request.robot_state, "robot_state", service_, &state, &scene);
  if (!isSuccess(code)) return true;
  const auto report = checkStateCollision(state, *scene->collision());
  for (const auto& contact : report.contacts) {
    sixdof_msgs::ContactInformation info;
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
  const std::string bounds = boundsViolation(state);
  response.valid = !report.colliding && bounds.empty();
  // The check itself succeeded: the code is SUCCESS, the message says why the state is invalid.
  std::string message = "state is valid";
  if (report.colliding) {
    message = std::to_string(report.contacts.size()) + " contact(s), e.g. " + describeContact(report.contacts.front());
  }
  if (!bounds.empty()) message = (report.colliding ? message + "; " : "") + bounds;
  code = makeSuccess(service_, message);
  return true;
}

template class ServiceCapability<StateValidityService>;

}  // namespace sixdof_planning
