#include "sixdof_planning/move_action_capability.h"

#include <sixdof_msgs/MotionPlanResponse.h>
#include <sixdof_msgs/MoveGroupAction.h>

#include "action_feedback.h"
#include "move_group_capability_impl.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

namespace {
const char* const kMoveGroupSource = "move_group";

bool isEmptyDiff(const sixdof_msgs::PlanningScene& diff) {
  return diff.is_diff && diff.world.collision_objects.empty() && diff.robot_state.attached_collision_objects.empty() &&
         diff.robot_state.joint_state.name.empty();
}
}  // namespace

void MoveGroupActionCapability::execute(const sixdof_msgs::MoveGroupGoalConstPtr& goal) {
  sixdof_msgs::MoveGroupResult result;
  auto finish = [&] { finishGoal<sixdof_msgs::MoveGroupFeedback>(server_.get(), result, kMoveGroupSource); };
  publishState<sixdof_msgs::MoveGroupFeedback>(server_.get(), "PLANNING");
  // The goal's scene diff holds for this goal only: it is applied to a copy of the scene.
  std::shared_ptr<const SceneStore> scene;
  const auto& diff = goal->planning_options.planning_scene_diff;
  if (!isEmptyDiff(diff)) {
    sixdof_core::RobotState state(context_->model());
    result.error_code = context_->currentState(kMoveGroupSource, &state);
    if (!isSuccess(result.error_code)) return finish();
    auto copy = std::make_shared<SceneStore>(*context_->scene());
    result.error_code = copy->apply(diff, state, kMoveGroupSource);
    if (!isSuccess(result.error_code)) {
      result.error_code.message = "planning_options.planning_scene_diff: " + result.error_code.message;
      return finish();
    }
    scene = copy;
  }
  sixdof_msgs::MotionPlanResponse plan;
  MotionPlanner(context_).plan(goal->request, kMoveGroupSource, &plan, scene);
  result.error_code = plan.error_code;
  result.trajectory_start = plan.trajectory_start;
  result.planned_trajectory = plan.trajectory;
  result.planning_time = plan.planning_time;
  if (!isSuccess(result.error_code) || goal->planning_options.plan_only) return finish();
  if (server_->isPreemptRequested()) {
    result.error_code = makeError(ErrorCode::PREEMPTED, "preempted after planning", kMoveGroupSource);
    return finish();
  }
  publishState<sixdof_msgs::MoveGroupFeedback>(server_.get(), "MONITOR");
  result.error_code = executor_->execute(plan.trajectory.joint_trajectory, kMoveGroupSource,
                                         [this] { return server_->isPreemptRequested() || !ros::ok(); });
  if (isSuccess(result.error_code)) result.executed_trajectory = plan.trajectory;
  finish();
}

template class ActionCapability<MoveGroupActionCapability, sixdof_msgs::MoveGroupAction>;

}  // namespace sixdof_planning
