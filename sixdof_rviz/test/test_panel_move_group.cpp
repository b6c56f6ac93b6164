// PlanningPanelLogic and GoalIk against the real move_group and simulator (rostest panel_move_group.test): plans and
// executions succeed, and a refused request's status carries move_group's words (the action's status text, a
// service's error report).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <moveit_msgs/PlanningScene.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include "sixdof_rviz/goal_ik.h"
#include "sixdof_rviz/link_poses.h"
#include "sixdof_rviz/planning_panel_logic.h"

namespace sixdof_rviz {
namespace {

// Hang guards only: planning and executing the sixdof arm's moves take seconds when healthy.
constexpr double kStartup = 60.0;
constexpr double kOperation = 60.0;

class PanelMoveGroupTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    std::string urdf;
    std::string srdf;
    ASSERT_TRUE(nh.getParam("robot_description", urdf) && nh.getParam("robot_description_semantic", srdf));
    model_ = std::make_shared<SemanticModel>(urdf, srdf);
  }
  static void TearDownTestSuite() { model_.reset(); }

  PanelMoveGroupTest() : logic_(nh_, model_, [this](const PanelStatus& s) { statuses_.push_back(s); }) {}

  void SetUp() override {
    ASSERT_TRUE(ros::service::waitForService("check_state_validity", ros::Duration(kStartup)));
    ASSERT_TRUE(spinUntil([this] { return logic_.connected() && logic_.currentState(); }, kStartup))
        << "move_group's actions or joint_states did not come up";
  }

  template <typename Condition>
  bool spinUntil(Condition condition, double seconds) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
    while (!condition()) {
      if (ros::WallTime::now() > deadline) return false;
      ros::spinOnce();
      ros::WallDuration(0.01).sleep();
    }
    return true;
  }

  // The status that ends the operation started last (the first that is not kInfo).
  PanelStatus outcome() {
    const size_t before = statuses_.size();
    const bool ended = spinUntil(
        [&] { return statuses_.size() > before && statuses_.back().level != PanelStatus::Level::kInfo; }, kOperation);
    EXPECT_TRUE(ended) << "no outcome within " << kOperation << " s";
    return ended ? statuses_.back() : PanelStatus{};
  }

  ros::NodeHandle nh_;
  static std::shared_ptr<const SemanticModel> model_;
  std::vector<PanelStatus> statuses_;
  PlanningPanelLogic logic_;
};

std::shared_ptr<const SemanticModel> PanelMoveGroupTest::model_;

PlanningSettings armSettings() {
  PlanningSettings settings;
  settings.group = "arm";
  settings.planning_time = 5.0;
  return settings;
}

TEST_F(PanelMoveGroupTest, PlansAndExecutesToANamedState) {
  logic_.plan(armSettings(), GoalSpec{GoalSource::kNamedState, "pick pose"});
  PanelStatus planned = outcome();
  RecordProperty("planned", planned.text);
  EXPECT_EQ(planned.level, PanelStatus::Level::kOk) << planned.text;
  EXPECT_EQ(planned.text.rfind("Plan succeeded: ", 0), 0u) << planned.text;
  ASSERT_TRUE(logic_.hasPlan());
  logic_.execute();
  PanelStatus executed = outcome();
  EXPECT_EQ(executed.level, PanelStatus::Level::kOk) << executed.text;
  EXPECT_EQ(executed.text, "Execute succeeded");
  // The robot is at the named state: joint_states after the execution.
  const NamedState* pick = model_->namedState("arm", "pick pose");
  ASSERT_NE(pick, nullptr);
  const ros::Time done = ros::Time::now();
  ASSERT_TRUE(spinUntil([&] { return logic_.currentState()->header.stamp >= done; }, kOperation));
  const auto& state = *logic_.currentState();
  for (size_t i = 0; i < state.name.size(); ++i) {
    auto it = pick->values.find(state.name[i]);
    if (it != pick->values.end()) EXPECT_NEAR(state.position[i], it->second, 0.01) << state.name[i];
  }
}

TEST_F(PanelMoveGroupTest, ARefusedGoalShowsMoveGroupsWords) {
  PlanningSettings settings = armSettings();
  settings.planner_id = "NoSuchPlanner";
  logic_.plan(settings, GoalSpec{GoalSource::kNamedState, "home pose"});
  const PanelStatus refused = outcome();
  RecordProperty("refused", refused.text);
  EXPECT_EQ(refused.level, PanelStatus::Level::kError);
  // "Plan failed: <CODE> (<val>): <move_group's words, naming the planner>"
  EXPECT_EQ(refused.text.rfind("Plan failed: ", 0), 0u) << refused.text;
  EXPECT_NE(refused.text.find("): "), std::string::npos) << "no words after the code: " << refused.text;
  EXPECT_NE(refused.text.find("NoSuchPlanner"), std::string::npos) << refused.text;
  EXPECT_FALSE(logic_.hasPlan());
}

TEST_F(PanelMoveGroupTest, RandomValidGoalIsWithinTheLimits) {
  std::string error;
  const auto goal = logic_.resolveGoal("arm", GoalSpec{GoalSource::kRandomValid, ""}, &error);
  ASSERT_TRUE(goal) << error;
  for (const auto& joint : model_->group("arm")->joints) {
    const ActiveJoint* limits = model_->activeJoint(joint);
    ASSERT_EQ(goal->count(joint), 1u) << joint;
    if (limits->bounded) {
      EXPECT_GE(goal->at(joint), limits->lower);
      EXPECT_LE(goal->at(joint), limits->upper);
    }
  }
}

GoalIkRequest ikRequest(const std::string& group, const Eigen::Isometry3d& pose, const std::string& frame) {
  GoalIkRequest request;
  request.group = group;
  request.tip_link = "link6";
  request.pose.header.frame_id = frame;
  request.pose.pose = tf2::toMsg(pose);
  return request;
}

TEST_F(PanelMoveGroupTest, GoalIkSolvesAndExplainsFailuresInMoveGroupsWords) {
  GoalIk ik(nh_);
  const LinkPoses fk(model_->robotModel());
  const Eigen::Isometry3d home = fk.compute(model_->namedState("arm", "home pose")->values).at("link6");
  const GoalIkOutcome solved = ik.solve(ikRequest("arm", home, fk.rootLink()));
  ASSERT_EQ(solved.kind, GoalIkOutcome::Kind::kValid) << solved.message;
  EXPECT_TRUE(fk.compute(solved.solution).at("link6").isApprox(home, 1e-3));

  Eigen::Isometry3d far = home;
  far.translation().x() = 3.0;  // beyond the arm's reach
  const GoalIkOutcome unreachable = ik.solve(ikRequest("arm", far, fk.rootLink()));
  RecordProperty("unreachable", unreachable.message);
  EXPECT_EQ(unreachable.kind, GoalIkOutcome::Kind::kNoSolution) << unreachable.message;
  // move_group's report, not the placeholder for a missing one.
  EXPECT_EQ(unreachable.message.find("no error report"), std::string::npos) << unreachable.message;
  EXPECT_NE(unreachable.message.find("reach"), std::string::npos) << unreachable.message;

  const GoalIkOutcome bad_group = ik.solve(ikRequest("legs", home, fk.rootLink()));
  RecordProperty("bad_group", bad_group.message);
  EXPECT_EQ(bad_group.kind, GoalIkOutcome::Kind::kError);
  EXPECT_EQ(bad_group.message.rfind("compute_ik failed: INVALID_GROUP_NAME: ", 0), 0u) << bad_group.message;
  EXPECT_NE(bad_group.message.find("legs"), std::string::npos) << bad_group.message;
}

// What the Planning Scene display relies on: move_group's latched full scene.
TEST_F(PanelMoveGroupTest, MonitoredSceneIsALatchedFullScene) {
  moveit_msgs::PlanningScene::ConstPtr scene;
  ros::Subscriber sub = nh_.subscribe<moveit_msgs::PlanningScene>(
      "move_group/monitored_planning_scene", 1,
      [&scene](const moveit_msgs::PlanningScene::ConstPtr& msg) { scene = msg; });
  ASSERT_TRUE(spinUntil([&scene] { return scene != nullptr; }, kStartup))
      << "nothing on move_group/monitored_planning_scene";
  EXPECT_FALSE(scene->is_diff);
}

}  // namespace
}  // namespace sixdof_rviz
