#include "sixdof_rviz/planning_panel_logic.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <moveit_msgs/GetStateValidity.h>
#include <moveit_msgs/MoveItErrorCodes.h>
#include <sixdof_msgs/error_code_names.h>

namespace sixdof_rviz {
namespace {

// MoveIt's default goal joint tolerance (moveit_commander's set_goal_joint_tolerance default).
constexpr double kGoalJointTolerance = 1e-4;

std::string formatSeconds(double seconds) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << seconds << " s";
  return out.str();
}

bool inUnitInterval(double factor) { return std::isfinite(factor) && factor > 0.0 && factor <= 1.0; }

// errorCodeName names an unknown value with its number already.
bool isErrorCodeConstant(int32_t val) {
  return std::any_of(sixdof_msgs::kMoveItErrorCodeNames.begin(), sixdof_msgs::kMoveItErrorCodeNames.end(),
                     [val](const auto& entry) { return entry.val == val; });
}

}  // namespace

PlanningPanelLogic::PlanningPanelLogic(const ros::NodeHandle& nh, std::shared_ptr<const SemanticModel> model,
                                       StatusCallback on_status)
    : nh_(nh), model_(std::move(model)), on_status_(std::move(on_status)), reports_(nh) {
  if (!model_) throw std::invalid_argument("PlanningPanelLogic: no robot model");
  // No spin thread: results arrive on nh's callback queue, i.e. in the GUI thread inside rviz.
  move_group_client_ = std::make_unique<MoveGroupClient>(nh_, "move_group", false);
  execute_client_ = std::make_unique<ExecuteClient>(nh_, "execute_trajectory", false);
  validity_client_ = nh_.serviceClient<moveit_msgs::GetStateValidity>("check_state_validity");
  joint_state_sub_ = nh_.subscribe<sensor_msgs::JointState>(
      "joint_states", 1, [this](const sensor_msgs::JointStateConstPtr& msg) { current_state_ = *msg; });
  goal_state_sub_ = nh_.subscribe<sensor_msgs::JointState>(
      kGoalStateTopic, 1, [this](const sensor_msgs::JointStateConstPtr& msg) { marker_goal_ = *msg; });
}

void PlanningPanelLogic::report(PanelStatus::Level level, const std::string& text) const {
  if (on_status_) on_status_(PanelStatus{level, text});
}

std::string PlanningPanelLogic::checkSettings(const PlanningSettings& settings) const {
  if (model_->group(settings.group) == nullptr) return "unknown planning group '" + settings.group + "'";
  if (settings.planner_id.empty()) return "planner id is empty";
  if (!std::isfinite(settings.planning_time) || settings.planning_time <= 0.0) {
    return "planning time must be > 0 s (got " + std::to_string(settings.planning_time) + ")";
  }
  if (settings.attempts < 1) return "planning attempts must be >= 1 (got " + std::to_string(settings.attempts) + ")";
  if (!inUnitInterval(settings.velocity_scaling)) {
    return "velocity scaling must be in (0, 1] (got " + std::to_string(settings.velocity_scaling) + ")";
  }
  if (!inUnitInterval(settings.acceleration_scaling)) {
    return "acceleration scaling must be in (0, 1] (got " + std::to_string(settings.acceleration_scaling) + ")";
  }
  return "";
}

std::optional<JointValues> PlanningPanelLogic::resolveGoal(const std::string& group_name, const GoalSpec& spec,
                                                           std::string* error) {
  const PlanningGroup* group = model_->group(group_name);
  if (group == nullptr) {
    *error = "unknown planning group '" + group_name + "'";
    return std::nullopt;
  }
  switch (spec.source) {
    case GoalSource::kNamedState: {
      const NamedState* state = model_->namedState(group_name, spec.named_state);
      if (state == nullptr) {
        *error = "group '" + group_name + "' has no named state '" + spec.named_state + "'";
        return std::nullopt;
      }
      return state->values;
    }
    case GoalSource::kGoalMarker: {
      if (!marker_goal_) {
        *error = std::string("no goal from the goal marker yet (nothing on ") + kGoalStateTopic + ")";
        return std::nullopt;
      }
      JointValues values;
      const auto& msg = *marker_goal_;
      for (size_t i = 0; i < msg.name.size() && i < msg.position.size(); ++i) values[msg.name[i]] = msg.position[i];
      JointValues goal;
      for (const auto& joint : group->joints) {
        auto it = values.find(joint);
        if (it == values.end()) {
          *error = "the goal marker's state has no joint '" + joint + "'";
          return std::nullopt;
        }
        goal[joint] = it->second;
      }
      return goal;
    }
    case GoalSource::kRandomValid:
      return randomValidGoal(*group, error);
  }
  *error = "unknown goal source";
  return std::nullopt;
}

std::optional<JointValues> PlanningPanelLogic::randomValidGoal(const PlanningGroup& group, std::string* error) {
  if (!validity_client_.exists()) {
    *error = "service '" + validity_client_.getService() + "' is not available (is move_group running?)";
    return std::nullopt;
  }
  for (int attempt = 0; attempt < kRandomGoalAttempts; ++attempt) {
    JointValues goal;
    moveit_msgs::GetStateValidity srv;
    srv.request.group_name = group.name;
    srv.request.robot_state.is_diff = true;
    if (current_state_) srv.request.robot_state.joint_state = *current_state_;
    auto& js = srv.request.robot_state.joint_state;
    js.velocity.clear();
    js.effort.clear();
    for (const auto& name : group.joints) {
      const ActiveJoint* joint = model_->activeJoint(name);
      double lower = joint->bounded ? joint->lower : -M_PI;
      double upper = joint->bounded ? joint->upper : M_PI;
      double value = std::uniform_real_distribution<double>(lower, upper)(rng_);
      goal[name] = value;
      auto it = std::find(js.name.begin(), js.name.end(), name);
      if (it == js.name.end()) {
        js.name.push_back(name);
        js.position.push_back(value);
      } else {
        js.position[it - js.name.begin()] = value;
      }
    }
    const std::string& service = validity_client_.getService();
    const uint64_t mark = reports_.mark();
    if (!validity_client_.call(srv)) {
      *error = reports_.explainFailure("call to '" + service + "' failed", service, mark);
      return std::nullopt;
    }
    if (srv.response.valid) return goal;
    // Invalid without a contact: a refused request (its report says why) or an invalid sample.
    if (srv.response.contacts.empty()) {
      const auto report = reports_.waitFor(service, mark, kErrorReportWait);
      if (report) {
        *error = "check_state_validity failed: " + describeReport(*report);
        return std::nullopt;
      }
    }
  }
  *error = "no valid random state of group '" + group.name + "' in " + std::to_string(kRandomGoalAttempts) + " samples";
  return std::nullopt;
}

std::optional<moveit_msgs::MotionPlanRequest> PlanningPanelLogic::buildRequest(const PlanningSettings& settings,
                                                                              const JointValues& goal,
                                                                              std::string* error) const {
  *error = checkSettings(settings);
  if (!error->empty()) return std::nullopt;
  const PlanningGroup* group = model_->group(settings.group);
  moveit_msgs::MotionPlanRequest request;
  // An empty diff start state means "the planner's current state", as MoveGroupInterface does by default.
  request.start_state.is_diff = true;
  request.group_name = settings.group;
  request.planner_id = settings.planner_id;
  request.num_planning_attempts = settings.attempts;
  request.allowed_planning_time = settings.planning_time;
  request.max_velocity_scaling_factor = settings.velocity_scaling;
  request.max_acceleration_scaling_factor = settings.acceleration_scaling;
  moveit_msgs::Constraints constraints;
  for (const auto& name : group->joints) {
    auto it = goal.find(name);
    if (it == goal.end()) {
      *error = "goal has no value for joint '" + name + "' of group '" + settings.group + "'";
      return std::nullopt;
    }
    const ActiveJoint* joint = model_->activeJoint(name);
    if (!std::isfinite(it->second) || (joint->bounded && (it->second < joint->lower || it->second > joint->upper))) {
      *error = "goal value " + std::to_string(it->second) + " of joint '" + name + "' is outside its limits";
      return std::nullopt;
    }
    moveit_msgs::JointConstraint jc;
    jc.joint_name = name;
    jc.position = it->second;
    jc.tolerance_above = kGoalJointTolerance;
    jc.tolerance_below = kGoalJointTolerance;
    jc.weight = 1.0;
    constraints.joint_constraints.push_back(jc);
  }
  for (const auto& [name, value] : goal) {
    if (std::find(group->joints.begin(), group->joints.end(), name) == group->joints.end()) {
      *error = "goal joint '" + name + "' is not in group '" + settings.group + "'";
      return std::nullopt;
    }
  }
  request.goal_constraints.push_back(constraints);
  return request;
}

moveit_msgs::MoveGroupGoal PlanningPanelLogic::buildMoveGroupGoal(const moveit_msgs::MotionPlanRequest& request,
                                                                  bool plan_only) {
  moveit_msgs::MoveGroupGoal goal;
  goal.request = request;
  goal.planning_options.plan_only = plan_only;
  goal.planning_options.planning_scene_diff.is_diff = true;
  goal.planning_options.planning_scene_diff.robot_state.is_diff = true;
  return goal;
}

PanelStatus PlanningPanelLogic::describeResult(const std::string& operation, const moveit_msgs::MoveItErrorCodes& code,
                                               const std::string& message, std::optional<double> planning_time,
                                               const std::string& success_detail) {
  PanelStatus status;
  std::ostringstream text;
  if (code.val == moveit_msgs::MoveItErrorCodes::SUCCESS) {
    status.level = PanelStatus::Level::kOk;
    text << operation << " succeeded";
    if (!success_detail.empty()) text << ": " << success_detail;
  } else {
    status.level = PanelStatus::Level::kError;
    text << operation << " failed: " << sixdof_msgs::errorCodeName(code.val);
    if (isErrorCodeConstant(code.val)) text << " (" << code.val << ")";
    if (!message.empty()) text << ": " << message;
  }
  if (planning_time) text << " (planning time " << formatSeconds(*planning_time) << ")";
  status.text = text.str();
  return status;
}

void PlanningPanelLogic::plan(const PlanningSettings& settings, const GoalSpec& goal) {
  sendMoveGroupGoal("Plan", settings, goal, true);
}

void PlanningPanelLogic::planAndExecute(const PlanningSettings& settings, const GoalSpec& goal) {
  sendMoveGroupGoal("Plan & Execute", settings, goal, false);
}

void PlanningPanelLogic::sendMoveGroupGoal(const std::string& operation, const PlanningSettings& settings,
                                           const GoalSpec& goal_spec, bool plan_only) {
  std::string error;
  auto goal = resolveGoal(settings.group, goal_spec, &error);
  if (!goal) return report(PanelStatus::Level::kError, operation + ": " + error);
  auto request = buildRequest(settings, *goal, &error);
  if (!request) return report(PanelStatus::Level::kError, operation + ": " + error);
  if (!move_group_client_->isServerConnected()) {
    return report(PanelStatus::Level::kError, operation + ": action server '" + nh_.resolveName("move_group") +
                                                  "' is not connected (is the planner node running?)");
  }
  report(PanelStatus::Level::kInfo, operation + ": sent to move_group...");
  move_group_client_->sendGoal(
      buildMoveGroupGoal(*request, plan_only),
      [this, operation](const actionlib::SimpleClientGoalState& state,
                        const moveit_msgs::MoveGroupResultConstPtr& result) {
        if (!result) {
          return report(PanelStatus::Level::kError,
                        operation + " failed: move_group ended in state " + state.toString() + " without a result");
        }
        if (result->error_code.val == moveit_msgs::MoveItErrorCodes::SUCCESS) {
          last_plan_ = result->planned_trajectory;
        }
        const auto& points = result->planned_trajectory.joint_trajectory.points;
        std::string detail = std::to_string(points.size()) + " waypoints";
        if (!points.empty()) detail += ", duration " + formatSeconds(points.back().time_from_start.toSec());
        on_status_(describeResult(operation, result->error_code, state.getText(), result->planning_time, detail));
      });
}

void PlanningPanelLogic::execute() {
  if (!last_plan_) return report(PanelStatus::Level::kError, "Execute: nothing to execute, plan first");
  if (!execute_client_->isServerConnected()) {
    return report(PanelStatus::Level::kError, "Execute: action server '" + nh_.resolveName("execute_trajectory") +
                                                  "' is not connected (is the planner node running?)");
  }
  moveit_msgs::ExecuteTrajectoryGoal goal;
  goal.trajectory = *last_plan_;
  report(PanelStatus::Level::kInfo, "Execute: sent to execute_trajectory...");
  execute_client_->sendGoal(goal, [this](const actionlib::SimpleClientGoalState& state,
                                         const moveit_msgs::ExecuteTrajectoryResultConstPtr& result) {
    if (!result) {
      return report(PanelStatus::Level::kError,
                    "Execute failed: execute_trajectory ended in state " + state.toString() + " without a result");
    }
    on_status_(describeResult("Execute", result->error_code, state.getText(), std::nullopt));
  });
}

void PlanningPanelLogic::stop() {
  bool connected = false;
  if (move_group_client_->isServerConnected()) {
    move_group_client_->cancelAllGoals();
    connected = true;
  }
  if (execute_client_->isServerConnected()) {
    execute_client_->cancelAllGoals();
    connected = true;
  }
  if (!connected) return report(PanelStatus::Level::kError, "Stop: move_group is not connected");
  report(PanelStatus::Level::kInfo, "Stop: cancel requested");
}

}  // namespace sixdof_rviz
