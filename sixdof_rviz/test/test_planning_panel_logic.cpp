// PlanningPanelLogic: request building, goal resolution and status texts (rostest: needs a master, no GUI).
// move_group is deliberately absent: the unavailable-planner paths are part of the behaviour under test.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_rviz/planning_panel_logic.h"

namespace sixdof_rviz {
namespace {

class PlanningPanelLogicTest : public ::testing::Test {
 protected:
  PlanningPanelLogicTest()
      : model_(std::make_shared<SemanticModel>(sixdof_core::readTextFile(SIXDOF_URDF_FILE),
                                               sixdof_core::readTextFile(SIXDOF_TEST_SRDF_FILE))),
        logic_(nh_, model_, [this](const PanelStatus& s) { statuses_.push_back(s); }) {}

  JointValues namedGoal(const std::string& group, const std::string& name) {
    std::string error;
    auto goal = logic_.resolveGoal(group, GoalSpec{GoalSource::kNamedState, name}, &error);
    EXPECT_TRUE(goal) << error;
    return goal.value_or(JointValues{});
  }

  std::string requestError(const PlanningSettings& settings, const JointValues& goal) {
    std::string error;
    EXPECT_FALSE(logic_.buildRequest(settings, goal, &error));
    return error;
  }

  ros::NodeHandle nh_;
  std::shared_ptr<const SemanticModel> model_;
  std::vector<PanelStatus> statuses_;
  PlanningPanelLogic logic_;
};

TEST_F(PlanningPanelLogicTest, RequestFromNamedGoalCarriesAllSettings) {
  PlanningSettings settings;
  settings.group = "arm";
  settings.planner_id = "RRTstar";
  settings.planning_time = 2.5;
  settings.attempts = 3;
  settings.velocity_scaling = 0.25;
  settings.acceleration_scaling = 0.5;
  std::string error;
  auto request = logic_.buildRequest(settings, namedGoal("arm", "home pose"), &error);
  ASSERT_TRUE(request) << error;
  EXPECT_EQ(request->group_name, "arm");
  EXPECT_EQ(request->planner_id, "RRTstar");
  EXPECT_DOUBLE_EQ(request->allowed_planning_time, 2.5);
  EXPECT_EQ(request->num_planning_attempts, 3);
  EXPECT_DOUBLE_EQ(request->max_velocity_scaling_factor, 0.25);
  EXPECT_DOUBLE_EQ(request->max_acceleration_scaling_factor, 0.5);
  // Start = the planner's current state.
  EXPECT_TRUE(request->start_state.is_diff);
  EXPECT_TRUE(request->start_state.joint_state.name.empty());
  ASSERT_EQ(request->goal_constraints.size(), 1u);
  const auto& joints = request->goal_constraints[0].joint_constraints;
  ASSERT_EQ(joints.size(), 6u);
  const std::vector<double> home = {0.0, -0.2, 0.9, 0.0, 0.87, 0.0};
  for (size_t i = 0; i < joints.size(); ++i) {
    EXPECT_EQ(joints[i].joint_name, "joint" + std::to_string(i + 1));
    EXPECT_DOUBLE_EQ(joints[i].position, home[i]);
    EXPECT_DOUBLE_EQ(joints[i].tolerance_above, 1e-4);
    EXPECT_DOUBLE_EQ(joints[i].tolerance_below, 1e-4);
    EXPECT_DOUBLE_EQ(joints[i].weight, 1.0);
  }
}

TEST_F(PlanningPanelLogicTest, GripperGoalUsesOnlyItsActiveJoint) {
  PlanningSettings settings;
  settings.group = "gripper";
  std::string error;
  auto request = logic_.buildRequest(settings, namedGoal("gripper", "open"), &error);
  ASSERT_TRUE(request) << error;
  ASSERT_EQ(request->goal_constraints.at(0).joint_constraints.size(), 1u);
  EXPECT_EQ(request->goal_constraints[0].joint_constraints[0].joint_name, "finger1_joint");
  EXPECT_DOUBLE_EQ(request->goal_constraints[0].joint_constraints[0].position, 0.04);
}

TEST_F(PlanningPanelLogicTest, MoveGroupGoalPlanOnlyFlag) {
  moveit_msgs::MotionPlanRequest request;
  request.group_name = "arm";
  auto plan = PlanningPanelLogic::buildMoveGroupGoal(request, true);
  EXPECT_TRUE(plan.planning_options.plan_only);
  EXPECT_EQ(plan.request.group_name, "arm");
  EXPECT_TRUE(plan.planning_options.planning_scene_diff.is_diff);
  EXPECT_FALSE(PlanningPanelLogic::buildMoveGroupGoal(request, false).planning_options.plan_only);
}

TEST_F(PlanningPanelLogicTest, BadSettingsAreRejectedNamingTheField) {
  const JointValues home = namedGoal("arm", "home pose");
  // One bad field per case (the others at their defaults) and the message that names it.
  const std::vector<std::pair<std::function<void(PlanningSettings*)>, std::string>> cases = {
      {[](PlanningSettings* s) { s->velocity_scaling = 0.0; },
       "velocity scaling must be in (0, 1] (got 0.000000)"},
      {[](PlanningSettings* s) { s->acceleration_scaling = 1.5; },
       "acceleration scaling must be in (0, 1] (got 1.500000)"},
      {[](PlanningSettings* s) { s->attempts = 0; }, "planning attempts must be >= 1 (got 0)"},
      {[](PlanningSettings* s) { s->planning_time = 0.0; }, "planning time must be > 0 s (got 0.000000)"},
      {[](PlanningSettings* s) { s->planner_id = ""; }, "planner id is empty"},
      {[](PlanningSettings* s) { s->group = "legs"; }, "unknown planning group 'legs'"},
  };
  for (const auto& [spoil, message] : cases) {
    PlanningSettings settings;
    spoil(&settings);
    EXPECT_EQ(requestError(settings, home), message);
  }
}

TEST_F(PlanningPanelLogicTest, BadGoalsAreRejectedNamingTheJoint) {
  JointValues goal = namedGoal("arm", "home pose");
  goal["joint2"] = 2.0;  // limit 1.92
  EXPECT_EQ(requestError(PlanningSettings{}, goal), "goal value 2.000000 of joint 'joint2' is outside its limits");
  goal = namedGoal("arm", "home pose");
  goal.erase("joint5");
  EXPECT_EQ(requestError(PlanningSettings{}, goal), "goal has no value for joint 'joint5' of group 'arm'");
  goal = namedGoal("arm", "home pose");
  goal["finger1_joint"] = 0.0;
  EXPECT_EQ(requestError(PlanningSettings{}, goal), "goal joint 'finger1_joint' is not in group 'arm'");
  std::string error;
  EXPECT_FALSE(logic_.resolveGoal("arm", GoalSpec{GoalSource::kNamedState, "dance"}, &error));
  EXPECT_EQ(error, "group 'arm' has no named state 'dance'");
}

TEST_F(PlanningPanelLogicTest, StatusTextsNameTheCodeAndCarryMoveGroupsWords) {
  moveit_msgs::MoveItErrorCodes code;
  code.val = moveit_msgs::MoveItErrorCodes::SUCCESS;
  PanelStatus ok = PlanningPanelLogic::describeResult("Plan", code, "", 0.1534, "12 waypoints, duration 2.000 s");
  EXPECT_EQ(ok.level, PanelStatus::Level::kOk);
  EXPECT_EQ(ok.text, "Plan succeeded: 12 waypoints, duration 2.000 s (planning time 0.153 s)");

  code.val = moveit_msgs::MoveItErrorCodes::PLANNING_FAILED;
  PanelStatus failed = PlanningPanelLogic::describeResult("Plan", code, "no path found within 5 s", 5.0);
  EXPECT_EQ(failed.level, PanelStatus::Level::kError);
  EXPECT_EQ(failed.text, "Plan failed: PLANNING_FAILED (-1): no path found within 5 s (planning time 5.000 s)");

  code.val = moveit_msgs::MoveItErrorCodes::CONTROL_FAILED;
  EXPECT_EQ(PlanningPanelLogic::describeResult("Execute", code, "", std::nullopt).text,
            "Execute failed: CONTROL_FAILED (-4)");
  code.val = -1234;
  EXPECT_EQ(PlanningPanelLogic::describeResult("Execute", code, "", std::nullopt).text,
            "Execute failed: unknown MoveIt error code -1234");
}

TEST_F(PlanningPanelLogicTest, MarkerGoalComesFromTheGoalStateTopic) {
  std::string error;
  EXPECT_FALSE(logic_.resolveGoal("arm", GoalSpec{GoalSource::kGoalMarker, ""}, &error));
  EXPECT_EQ(error, "no goal from the goal marker yet (nothing on sixdof_rviz/goal_state)");

  ros::Publisher pub = nh_.advertise<sensor_msgs::JointState>(kGoalStateTopic, 1, true);
  sensor_msgs::JointState goal;
  goal.name = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "finger1_joint", "finger2_joint"};
  goal.position = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.02, 0.02};
  pub.publish(goal);
  for (int i = 0; i < 1000 && !logic_.markerGoal(); ++i) {
    ros::Duration(0.01).sleep();
    ros::spinOnce();
  }
  auto values = logic_.resolveGoal("arm", GoalSpec{GoalSource::kGoalMarker, ""}, &error);
  ASSERT_TRUE(values) << error;
  EXPECT_EQ(values->size(), 6u);  // only the group's joints
  EXPECT_DOUBLE_EQ(values->at("joint6"), 0.6);
}

TEST_F(PlanningPanelLogicTest, WithoutPlannerTheStatusSaysSo) {
  std::string error;
  EXPECT_FALSE(logic_.resolveGoal("arm", GoalSpec{GoalSource::kRandomValid, ""}, &error));
  EXPECT_EQ(error, "service '/check_state_validity' is not available (is move_group running?)");

  logic_.plan(PlanningSettings{}, GoalSpec{GoalSource::kNamedState, "home pose"});
  ASSERT_EQ(statuses_.size(), 1u);
  EXPECT_EQ(statuses_[0].level, PanelStatus::Level::kError);
  EXPECT_EQ(statuses_[0].text, "Plan: action server '/move_group' is not connected (is the planner node running?)");

  logic_.plan(PlanningSettings{}, GoalSpec{GoalSource::kNamedState, "dance"});
  EXPECT_EQ(statuses_.back().text, "Plan: group 'arm' has no named state 'dance'");

  PlanningSettings bad;
  bad.velocity_scaling = 2.0;
  logic_.planAndExecute(bad, GoalSpec{GoalSource::kNamedState, "home pose"});
  EXPECT_EQ(statuses_.back().text, "Plan & Execute: velocity scaling must be in (0, 1] (got 2.000000)");

  logic_.execute();
  EXPECT_FALSE(logic_.hasPlan());
  EXPECT_EQ(statuses_.back().text, "Execute: nothing to execute, plan first");
  logic_.stop();
  EXPECT_EQ(statuses_.back().text, "Stop: move_group is not connected");
}

}  // namespace
}  // namespace sixdof_rviz
