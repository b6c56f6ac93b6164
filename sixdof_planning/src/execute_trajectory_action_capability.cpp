#include "sixdof_planning/execute_trajectory_action_capability.h"

#include <moveit_msgs/ExecuteTrajectoryAction.h>

#include "action_feedback.h"
#include "move_group_capability_impl.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

namespace {
const char* const kExecuteSource = "execute_trajectory";
}  // namespace

void ExecuteTrajectoryActionCapability::execute(const moveit_msgs::ExecuteTrajectoryGoalConstPtr& goal) {
  publishState<moveit_msgs::ExecuteTrajectoryFeedback>(server_.get(), "MONITOR");
  moveit_msgs::ExecuteTrajectoryResult result;
  ErrorCode code;
  if (!goal->trajectory.multi_dof_joint_trajectory.joint_names.empty()) {
    code = makeError(ErrorCode::INVALID_MOTION_PLAN,
                     "trajectory.multi_dof_joint_trajectory is not supported (the robot model has no multi-DOF joints)",
                     kExecuteSource);
  } else {
    code = executor_->execute(goal->trajectory.joint_trajectory, kExecuteSource,
                              [this] { return server_->isPreemptRequested() || !ros::ok(); });
  }
  finishGoal<moveit_msgs::ExecuteTrajectoryFeedback>(server_.get(), &result, code, kExecuteSource);
}

template class ActionCapability<ExecuteTrajectoryActionCapability, moveit_msgs::ExecuteTrajectoryAction>;

}  // namespace sixdof_planning
