#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include <actionlib/client/simple_action_client.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <moveit_msgs/ExecuteTrajectoryAction.h>
#include <moveit_msgs/MoveGroupAction.h>

#include "sixdof_rviz/error_reports.h"
#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

// Latched topic on which the GoalState display publishes the goal robot state (all joints).
constexpr char kGoalStateTopic[] = "sixdof_rviz/goal_state";

struct PlanningSettings {
  std::string group = "arm";
  std::string planner_id = "RRTConnect";
  double planning_time = 5.0;  // seconds, > 0
  int attempts = 1;            // >= 1
  double velocity_scaling = 1.0;      // (0, 1]
  double acceleration_scaling = 1.0;  // (0, 1]
};

enum class GoalSource { kNamedState, kGoalMarker, kRandomValid };

struct GoalSpec {
  GoalSource source = GoalSource::kNamedState;
  std::string named_state;  // for kNamedState
};

struct PanelStatus {
  enum class Level { kInfo, kOk, kError };
  Level level = Level::kInfo;
  std::string text;
};

// Everything the MotionPlanningPanel does, without any GUI: builds moveit_msgs MotionPlanRequest / MoveGroup goals
// from the panel's settings, talks to move_group (actions move_group and execute_trajectory, service
// check_state_validity) and turns its answers into the status line: the MoveItErrorCodes name and move_group's
// words (an action's status text; a service's ErrorReport). Callbacks run on the node handle's callback queue (in
// rviz: the GUI thread).
class PlanningPanelLogic {
 public:
  using StatusCallback = std::function<void(const PanelStatus&)>;

  // `nh` is the namespace of the move_group node's interfaces (its parent namespace, e.g. "/").
  PlanningPanelLogic(const ros::NodeHandle& nh, std::shared_ptr<const SemanticModel> model, StatusCallback on_status);

  // Empty when the settings are usable, else a message naming the bad field.
  std::string checkSettings(const PlanningSettings& settings) const;
  // Joint goal of `group` from `spec`; nullopt with `error` set when it cannot be resolved.
  std::optional<JointValues> resolveGoal(const std::string& group, const GoalSpec& spec, std::string* error);
  // nullopt with `error` set when settings or goal are unusable.
  std::optional<moveit_msgs::MotionPlanRequest> buildRequest(const PlanningSettings& settings, const JointValues& goal,
                                                            std::string* error) const;
  static moveit_msgs::MoveGroupGoal buildMoveGroupGoal(const moveit_msgs::MotionPlanRequest& request, bool plan_only);

  // Status line for the result of `operation` ("Plan", "Execute", "Plan & Execute"): on success `success_detail`
  // after "succeeded" (e.g. the number of waypoints); on failure the code's name and value, then `message`
  // (move_group's words) when there is one.
  static PanelStatus describeResult(const std::string& operation, const moveit_msgs::MoveItErrorCodes& code,
                                    const std::string& message, std::optional<double> planning_time,
                                    const std::string& success_detail = "");

  // Asynchronous; the outcome arrives through the status callback.
  void plan(const PlanningSettings& settings, const GoalSpec& goal);
  void planAndExecute(const PlanningSettings& settings, const GoalSpec& goal);
  void execute();  // executes the last successful plan
  void stop();

  bool hasPlan() const { return last_plan_.has_value(); }
  // Both of move_group's action servers (move_group, execute_trajectory) are connected.
  bool connected() const { return move_group_client_->isServerConnected() && execute_client_->isServerConnected(); }
  const std::optional<sensor_msgs::JointState>& currentState() const { return current_state_; }
  const std::optional<sensor_msgs::JointState>& markerGoal() const { return marker_goal_; }
  void setRandomSeed(uint32_t seed) { rng_.seed(seed); }
  // Maximum random samples tried for a random valid goal.
  static constexpr int kRandomGoalAttempts = 100;

 private:
  using MoveGroupClient = actionlib::SimpleActionClient<moveit_msgs::MoveGroupAction>;
  using ExecuteClient = actionlib::SimpleActionClient<moveit_msgs::ExecuteTrajectoryAction>;

  void sendMoveGroupGoal(const std::string& operation, const PlanningSettings& settings, const GoalSpec& goal,
                         bool plan_only);
  std::optional<JointValues> randomValidGoal(const PlanningGroup& group, std::string* error);
  void report(PanelStatus::Level level, const std::string& text) const;

  ros::NodeHandle nh_;
  std::shared_ptr<const SemanticModel> model_;
  StatusCallback on_status_;
  std::unique_ptr<MoveGroupClient> move_group_client_;
  std::unique_ptr<ExecuteClient> execute_client_;
  ros::ServiceClient validity_client_;
  ErrorReports reports_;
  ros::Subscriber joint_state_sub_;
  ros::Subscriber goal_state_sub_;
  std::optional<sensor_msgs::JointState> current_state_;
  std::optional<sensor_msgs::JointState> marker_goal_;
  std::optional<moveit_msgs::RobotTrajectory> last_plan_;
  std::mt19937 rng_{42};
};

}  // namespace sixdof_rviz
