// GoalStateDisplay's IK worker: the thread that turns the latest dragged pose into compute_ik and
// check_state_validity calls (throttled by "IK Rate"), off rviz's render thread; update() shows the outcome.
#include <chrono>

#include <sixdof_msgs/GetPositionIK.h>
#include <sixdof_msgs/GetStateValidity.h>
#include <sixdof_msgs/MoveItErrorCodes.h>

#include "goal_state_display.h"
#include "sixdof_rviz/planning_panel_logic.h"

namespace sixdof_rviz {

void GoalStateDisplay::ikLoop() {
  using Clock = std::chrono::steady_clock;
  Clock::time_point next_call = Clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || pending_request_.has_value(); });
    // Throttle: wait out the rest of the period, collecting newer poses meanwhile.
    wake_.wait_until(lock, next_call, [this] { return stop_; });
    if (stop_) return;
    IkRequest request = *pending_request_;
    pending_request_.reset();
    const double period = ik_period_;
    lock.unlock();
    next_call = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period));
    IkOutcome outcome = solve(request);
    lock.lock();
    outcome_ = outcome;
  }
}

GoalStateDisplay::IkOutcome GoalStateDisplay::solve(const IkRequest& request) {
  ros::NodeHandle nh;
  sixdof_msgs::GetPositionIK ik;
  ik.request.ik_request.group_name = request.group;
  ik.request.ik_request.ik_link_name = request.tip_link;
  ik.request.ik_request.pose_stamped = request.pose;
  ik.request.ik_request.robot_state.joint_state = request.seed;
  ik.request.ik_request.robot_state.is_diff = true;
  // Collisions are reported separately (check_state_validity) so that a colliding goal is still shown.
  ik.request.ik_request.avoid_collisions = false;
  ros::ServiceClient ik_client = nh.serviceClient<sixdof_msgs::GetPositionIK>("compute_ik");
  if (!ik_client.call(ik)) {
    return {IkOutcome::Kind::kError, {}, "service '" + ik_client.getService() + "' is not available"};
  }
  const auto& code = ik.response.error_code;
  if (code.val == sixdof_msgs::MoveItErrorCodes::NO_IK_SOLUTION) {
    return {IkOutcome::Kind::kNoSolution, {}, "no IK solution" + (code.message.empty() ? "" : ": " + code.message)};
  }
  if (code.val != sixdof_msgs::MoveItErrorCodes::SUCCESS) {
    return {IkOutcome::Kind::kError, {}, PlanningPanelLogic::describeResult("compute_ik", code, std::nullopt).text};
  }
  IkOutcome outcome{IkOutcome::Kind::kValid, {}, "reachable"};
  const auto& js = ik.response.solution.joint_state;
  for (size_t i = 0; i < js.name.size() && i < js.position.size(); ++i) outcome.solution[js.name[i]] = js.position[i];

  sixdof_msgs::GetStateValidity validity;
  validity.request.group_name = request.group;
  validity.request.robot_state = ik.response.solution;
  ros::ServiceClient validity_client = nh.serviceClient<sixdof_msgs::GetStateValidity>("check_state_validity");
  if (!validity_client.call(validity)) {
    return {IkOutcome::Kind::kError, outcome.solution,
            "service '" + validity_client.getService() + "' is not available"};
  }
  if (validity.response.error_code.val != sixdof_msgs::MoveItErrorCodes::SUCCESS) {
    return {IkOutcome::Kind::kError, outcome.solution,
            PlanningPanelLogic::describeResult("check_state_validity", validity.response.error_code, std::nullopt)
                .text};
  }
  if (!validity.response.valid) {
    outcome.kind = IkOutcome::Kind::kInCollision;
    outcome.message = "goal in collision";
    for (const auto& contact : validity.response.contacts) {
      outcome.message += " (" + contact.contact_body_1 + " - " + contact.contact_body_2 + ")";
      break;  // the first contact names the problem well enough in a status line
    }
  }
  return outcome;
}

}  // namespace sixdof_rviz
