#include "sixdof_planning/capabilities.h"
#include "sixdof_planning/conversions.h"

namespace sixdof_planning {

namespace {
const char* const kMoveGroupSource = "move_group";
const char* const kExecuteSource = "execute_trajectory";

template <typename Feedback, typename Server>
void publishState(Server* server, const std::string& state) {
  Feedback feedback;
  feedback.state = state;
  server->publishFeedback(feedback);
}

// Ends the server's current goal by its error code (PREEMPTED -> preempted, success -> succeeded, else aborted),
// logs it under `source` and reports the server idle.
template <typename Feedback, typename Server, typename Result>
void finishGoal(Server* server, const Result& result, const char* source) {
  ROS_INFO_STREAM(source << ": " << errorCodeName(result.error_code.val) << " " << result.error_code.message);
  if (result.error_code.val == ErrorCode::PREEMPTED) {
    server->setPreempted(result, result.error_code.message);
  } else if (isSuccess(result.error_code)) {
    server->setSucceeded(result, result.error_code.message);
  } else {
    server->setAborted(result, result.error_code.message);
  }
  publishState<Feedback>(server, "IDLE");
}

bool isEmptyDiff(const sixdof_msgs::PlanningScene& diff) {
  return diff.is_diff && diff.world.collision_objects.empty() && diff.robot_state.attached_collision_objects.empty() &&
         diff.robot_state.joint_state.name.empty();
}
}  // namespace

MoveGroupActionCapability::MoveGroupActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor)
    : context_(context),
      executor_(executor),
      planner_(context),
      server_(context->nodeHandle(), "move_group", [this](const auto& goal) { execute(goal); }, false) {
  server_.start();
}

void MoveGroupActionCapability::execute(const sixdof_msgs::MoveGroupGoalConstPtr& goal) {
  sixdof_msgs::MoveGroupResult result;
  auto finish = [&] { finishGoal<sixdof_msgs::MoveGroupFeedback>(&server_, result, kMoveGroupSource); };
  publishState<sixdof_msgs::MoveGroupFeedback>(&server_, "PLANNING");
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
  planner_.plan(goal->request, kMoveGroupSource, &plan, scene);
  result.error_code = plan.error_code;
  result.trajectory_start = plan.trajectory_start;
  result.planned_trajectory = plan.trajectory;
  result.planning_time = plan.planning_time;
  if (!isSuccess(result.error_code) || goal->planning_options.plan_only) return finish();
  if (server_.isPreemptRequested()) {
    result.error_code = makeError(ErrorCode::PREEMPTED, "preempted after planning", kMoveGroupSource);
    return finish();
  }
  publishState<sixdof_msgs::MoveGroupFeedback>(&server_, "MONITOR");
  result.error_code = executor_->execute(plan.trajectory.joint_trajectory, kMoveGroupSource,
                                         [this] { return server_.isPreemptRequested() || !ros::ok(); });
  if (isSuccess(result.error_code)) result.executed_trajectory = plan.trajectory;
  finish();
}

ExecuteTrajectoryActionCapability::ExecuteTrajectoryActionCapability(MoveGroupContext* context,
                                                                     TrajectoryExecutor* executor)
    : context_(context),
      executor_(executor),
      server_(context->nodeHandle(), "execute_trajectory", [this](const auto& goal) { execute(goal); }, false) {
  server_.start();
}

void ExecuteTrajectoryActionCapability::execute(const sixdof_msgs::ExecuteTrajectoryGoalConstPtr& goal) {
  publishState<sixdof_msgs::ExecuteTrajectoryFeedback>(&server_, "MONITOR");
  sixdof_msgs::ExecuteTrajectoryResult result;
  result.error_code = executor_->execute(goal->trajectory.joint_trajectory, kExecuteSource,
                                         [this] { return server_.isPreemptRequested() || !ros::ok(); });
  finishGoal<sixdof_msgs::ExecuteTrajectoryFeedback>(&server_, result, kExecuteSource);
}

MoveGroupNode::MoveGroupNode(ros::NodeHandle nh, ros::NodeHandle private_nh) {
  context_ = std::make_unique<MoveGroupContext>(nh, loadConfig(nh, private_nh));
  executor_ = std::make_unique<TrajectoryExecutor>(context_.get());
  fk_ = std::make_unique<ForwardKinematicsService>(context_.get());
  ik_ = std::make_unique<InverseKinematicsService>(context_.get());
  plan_ = std::make_unique<MotionPlanService>(context_.get());
  cartesian_ = std::make_unique<CartesianPathService>(context_.get());
  validity_ = std::make_unique<StateValidityService>(context_.get());
  get_scene_ = std::make_unique<GetPlanningSceneService>(context_.get());
  apply_scene_ = std::make_unique<ApplyPlanningSceneService>(context_.get());
  move_group_ = std::make_unique<MoveGroupActionCapability>(context_.get(), executor_.get());
  execute_trajectory_ = std::make_unique<ExecuteTrajectoryActionCapability>(context_.get(), executor_.get());
}

}  // namespace sixdof_planning
