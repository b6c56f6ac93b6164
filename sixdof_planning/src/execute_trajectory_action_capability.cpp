#include "sixdof_planning/execute_trajectory_action_capability.h"

#include <sixdof_msgs/ExecuteTrajectoryAction.h>

#include "action_feedback.h"
#include "move_group_capability_impl.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

namespace {
const char* const kExecuteSource = "execute_trajectory";
}  // namespace

void ExecuteTrajectoryActionCapability::execute(const sixdof_msgs::ExecuteTrajectoryGoalConstPtr& goal) {
  publishState<sixdof_msgs::ExecuteTrajectoryFeedback>(server_.get(), "MONITOR");
  sixdof_msgs::ExecuteTrajectoryResult result;
  result.error_code = executor_->execute(goal->trajectory.joint_trajectory, kExecuteSource,
                                         [this] { return server_->isPreemptRequested() || !ros::ok(); });
  finishGoal<sixdof_msgs::ExecuteTrajectoryFeedback>(server_.get(), result, kExecuteSource);
}

template class ActionCapability<ExecuteTrajectoryActionCapability, sixdof_msgs::ExecuteTrajectoryAction>;

}  // namespace sixdof_planning
