#include "sixdof_planning/execute_trajectory_action_capability.h"

#include <actionlib/server/simple_action_server.h>
#include <sixdof_msgs/ExecuteTrajectoryAction.h>

#include "action_feedback.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

namespace {
const char* const kExecuteSource = "execute_trajectory";
}  // namespace

ExecuteTrajectoryActionCapability::ExecuteTrajectoryActionCapability(MoveGroupContext* context,
                                                                     TrajectoryExecutor* executor)
    : context_(context),
      executor_(executor),
      server_(std::make_unique<actionlib::SimpleActionServer<sixdof_msgs::ExecuteTrajectoryAction>>(
          context->nodeHandle(), "execute_trajectory", [this](const auto& goal) { execute(goal); }, false)) {
  server_->start();
}

ExecuteTrajectoryActionCapability::~ExecuteTrajectoryActionCapability() = default;

void ExecuteTrajectoryActionCapability::execute(const sixdof_msgs::ExecuteTrajectoryGoalConstPtr& goal) {
  publishState<sixdof_msgs::ExecuteTrajectoryFeedback>(server_.get(), "MONITOR");
  sixdof_msgs::ExecuteTrajectoryResult result;
  result.error_code = executor_->execute(goal->trajectory.joint_trajectory, kExecuteSource,
                                         [this] { return server_->isPreemptRequested() || !ros::ok(); });
  finishGoal<sixdof_msgs::ExecuteTrajectoryFeedback>(server_.get(), result, kExecuteSource);
}

}  // namespace sixdof_planning
