#include "sixdof_planning/move_action_capability.h"

#include <moveit_msgs/MotionPlanResponse.h>
#include <moveit_msgs/MoveGroupAction.h>

#include "action_feedback.h"
#include "move_group_capability_impl.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

namespace {
const char* const kMoveGroupSource = "move_group";

// A diff that changes nothing (MoveGroupInterface sends one with every goal): only is_diff set, or not even that.
bool isEmptyDiff(const moveit_msgs::PlanningScene& diff) {
  moveit_msgs::PlanningScene empty;
  empty.is_diff = diff.is_diff;
  empty.robot_state.is_diff = diff.robot_state.is_diff;
  return diff.is_diff && diff == empty;
}

// PlanningOptions sixdof does not offer: looking around and replanning (their counts and delays only matter with
// them).
ErrorCode checkPlanningOptions(const moveit_msgs::PlanningOptions& options) {
  if (options.look_around) {
    return makeError(ErrorCode::FAILURE, "planning_options.look_around is not supported", kMoveGroupSource);
  }
  if (options.replan) {
    return makeError(ErrorCode::FAILURE,
                     "planning_options.replan is not supported: a failed execution ends the goal (plan again)",
                     kMoveGroupSource);
  }
  return makeSuccess(kMoveGroupSource);
}
}  // namespace

void MoveGroupActionCapability::execute(const moveit_msgs::MoveGroupGoalConstPtr& goal) {
  moveit_msgs::MoveGroupResult result;
  publishState<moveit_msgs::MoveGroupFeedback>(server_.get(), "PLANNING");
  const ErrorCode code = run(*goal, &result);
  finishGoal<moveit_msgs::MoveGroupFeedback>(server_.get(), &result, code, kMoveGroupSource);
}

ErrorCode MoveGroupActionCapability::run(const moveit_msgs::MoveGroupGoal& goal, moveit_msgs::MoveGroupResult* result) {
  ErrorCode code = checkPlanningOptions(goal.planning_options);
  if (!isSuccess(code)) return code;
  // The goal's scene diff holds for this goal only: it is applied to a copy of the scene.
  std::shared_ptr<const SceneStore> scene;
  const auto& diff = goal.planning_options.planning_scene_diff;
  if (!isEmptyDiff(diff)) {
    sixdof_core::RobotState state(context_->model());
    code = context_->currentState(kMoveGroupSource, &state);
    if (!isSuccess(code)) return code;
    auto copy = std::make_shared<SceneStore>(*context_->scene());
    code = copy->apply(diff, state, kMoveGroupSource);
    if (!isSuccess(code)) {
      code.message = "planning_options.planning_scene_diff: " + code.message;
      return code;
    }
    scene = copy;
  }
  moveit_msgs::MotionPlanResponse plan;
  code = MotionPlanner(context_).plan(goal.request, kMoveGroupSource, &plan, scene);
  result->trajectory_start = plan.trajectory_start;
  result->planned_trajectory = plan.trajectory;
  result->planning_time = plan.planning_time;
  if (!isSuccess(code) || goal.planning_options.plan_only) return code;
  if (server_->isPreemptRequested()) return makeError(ErrorCode::PREEMPTED, "preempted after planning", kMoveGroupSource);
  publishState<moveit_msgs::MoveGroupFeedback>(server_.get(), "MONITOR");
  code = executor_->execute(plan.trajectory.joint_trajectory, kMoveGroupSource,
                            [this] { return server_->isPreemptRequested() || !ros::ok(); });
  if (isSuccess(code)) result->executed_trajectory = plan.trajectory;
  return code;
}

template class ActionCapability<MoveGroupActionCapability, moveit_msgs::MoveGroupAction>;

}  // namespace sixdof_planning
