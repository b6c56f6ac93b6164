#include "sixdof_rviz/goal_ik.h"

#include <moveit_msgs/GetPositionIK.h>
#include <moveit_msgs/GetStateValidity.h>
#include <moveit_msgs/MoveItErrorCodes.h>
#include <sixdof_msgs/error_code_names.h>

namespace sixdof_rviz {

GoalIk::GoalIk(const ros::NodeHandle& nh) : nh_(nh), reports_(nh) {}

std::string GoalIk::callFailure(ros::ServiceClient& client, uint64_t mark) const {
  if (!client.exists()) return "service '" + client.getService() + "' is not available (is move_group running?)";
  return reports_.explainFailure("call to '" + client.getService() + "' failed", client.getService(), mark);
}

GoalIkOutcome GoalIk::solve(const GoalIkRequest& request) {
  using Kind = GoalIkOutcome::Kind;
  moveit_msgs::GetPositionIK ik;
  ik.request.ik_request.group_name = request.group;
  ik.request.ik_request.ik_link_name = request.tip_link;
  ik.request.ik_request.pose_stamped = request.pose;
  ik.request.ik_request.robot_state.joint_state = request.seed;
  ik.request.ik_request.robot_state.is_diff = true;
  ik.request.ik_request.avoid_collisions = false;
  ros::ServiceClient ik_client = nh_.serviceClient<moveit_msgs::GetPositionIK>("compute_ik");
  uint64_t mark = reports_.mark();
  if (!ik_client.call(ik)) return {Kind::kError, {}, callFailure(ik_client, mark)};
  const int32_t code = ik.response.error_code.val;
  if (code == moveit_msgs::MoveItErrorCodes::NO_IK_SOLUTION) {
    // move_group's words say that there is no solution, and why.
    const auto report = reports_.waitFor(ik_client.getService(), mark, kErrorReportWait);
    if (report) return {Kind::kNoSolution, {}, describeReport(*report)};
    return {Kind::kNoSolution, {}, "no IK solution (no error report from move_group on " + reports_.topic() + ")"};
  }
  if (code != moveit_msgs::MoveItErrorCodes::SUCCESS) {
    return {Kind::kError, {},
            reports_.explainFailure("compute_ik failed: " + sixdof_msgs::errorCodeName(code), ik_client.getService(),
                                    mark)};
  }
  GoalIkOutcome outcome{Kind::kValid, {}, "reachable"};
  const auto& js = ik.response.solution.joint_state;
  for (size_t i = 0; i < js.name.size() && i < js.position.size(); ++i) outcome.solution[js.name[i]] = js.position[i];

  moveit_msgs::GetStateValidity validity;
  validity.request.group_name = request.group;
  validity.request.robot_state = ik.response.solution;
  ros::ServiceClient validity_client = nh_.serviceClient<moveit_msgs::GetStateValidity>("check_state_validity");
  mark = reports_.mark();
  if (!validity_client.call(validity)) return {Kind::kError, outcome.solution, callFailure(validity_client, mark)};
  if (validity.response.valid) return outcome;
  if (!validity.response.contacts.empty()) {
    const auto& contact = validity.response.contacts.front();  // the first contact names the problem well enough
    outcome.kind = Kind::kInCollision;
    outcome.message = "goal in collision (" + contact.contact_body_1 + " - " + contact.contact_body_2 + ")";
    return outcome;
  }
  // Invalid without a contact: a refused request (its report says why) or a state move_group finds invalid.
  const auto report = reports_.waitFor(validity_client.getService(), mark, kErrorReportWait);
  if (report) return {Kind::kError, outcome.solution, "check_state_validity failed: " + describeReport(*report)};
  outcome.kind = Kind::kInCollision;
  outcome.message = "goal state invalid (check_state_validity)";
  return outcome;
}

}  // namespace sixdof_rviz
