// SemanticModel, LinkPoses and TrajectoryAnimation against the project's URDF and the test SRDF (no ROS master).
#include <cmath>

#include <gtest/gtest.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_rviz/link_poses.h"
#include "sixdof_rviz/semantic_model.h"
#include "sixdof_rviz/trajectory_animation.h"

namespace sixdof_rviz {
namespace {

std::string urdfXml() { return sixdof_core::readTextFile(SIXDOF_URDF_FILE); }
std::string srdfXml() { return sixdof_core::readTextFile(SIXDOF_TEST_SRDF_FILE); }

TEST(SemanticModel, ResolvesChainJointsAndSubgroups) {
  SemanticModel model(urdfXml(), srdfXml());
  const PlanningGroup* arm = model.group("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_EQ(arm->joints, (std::vector<std::string>{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"}));
  EXPECT_EQ(arm->base_link, "base_link");
  EXPECT_EQ(arm->tip_link, "link6");
  const PlanningGroup* gripper = model.group("gripper");
  ASSERT_NE(gripper, nullptr);
  // finger2_joint mimics finger1_joint: not an independent goal variable.
  EXPECT_EQ(gripper->joints, std::vector<std::string>{"finger1_joint"});
  EXPECT_TRUE(gripper->tip_link.empty());
  const PlanningGroup* both = model.group("arm_with_gripper");
  ASSERT_NE(both, nullptr);
  EXPECT_EQ(both->joints.size(), 7u);
  EXPECT_EQ(model.group("legs"), nullptr);
}

TEST(SemanticModel, NamedStatesPerGroup) {
  SemanticModel model(urdfXml(), srdfXml());
  EXPECT_EQ(model.namedStates("arm"), (std::vector<std::string>{"home pose", "pick pose"}));
  EXPECT_EQ(model.namedStates("gripper"), (std::vector<std::string>{"open", "close"}));
  const NamedState* home = model.namedState("arm", "home pose");
  ASSERT_NE(home, nullptr);
  EXPECT_DOUBLE_EQ(home->values.at("joint3"), 0.9);
  EXPECT_EQ(model.namedState("gripper", "home pose"), nullptr);
  const ActiveJoint* joint2 = model.activeJoint("joint2");
  ASSERT_NE(joint2, nullptr);
  EXPECT_DOUBLE_EQ(joint2->lower, -1.92);
  EXPECT_DOUBLE_EQ(joint2->upper, 1.92);
}

void expectInvalid(const std::string& srdf, const std::string& fragment) {
  try {
    SemanticModel model(urdfXml(), srdf);
    ADD_FAILURE() << "accepted an SRDF that should fail with '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SemanticModel, RejectsBadSrdfNamingTheProblem) {
  expectInvalid("", "empty semantic description");
  expectInvalid("<robot", "XML error");
  expectInvalid(R"(<robot name="sixdof"><group name="arm"><chain base_link="base_link" tip_link="nolink"/></group></robot>)",
                "unknown link 'nolink'");
  expectInvalid(R"(<robot name="sixdof"><group name="a"><group name="b"/></group><group name="b"><group name="a"/></group>
                   </robot>)",
                "contains itself");
  expectInvalid(R"(<robot name="sixdof"><group name="g"><joint name="finger1_joint"/></group>
                   <group_state name="s" group="g"/></robot>)",
                "misses joint 'finger1_joint'");
  expectInvalid(R"(<robot name="sixdof"><group_state name="s" group="nogroup"/></robot>)", "unknown group 'nogroup'");
  EXPECT_THROW(SemanticModel("<robot name='x'/>", srdfXml()), std::invalid_argument);
}

TEST(LinkPoses, ZeroStateMatchesDesignContract) {
  SemanticModel model(urdfXml(), srdfXml());
  LinkPoses fk(model.robotModel());
  EXPECT_EQ(fk.rootLink(), "base_link");
  const LinkPoseMap poses = fk.compute({});
  // docs/design.md: at zero the forearm is horizontal along +x; link6 origin at x = 0.12 + 0.18 + 0.08,
  // z = 0.10 + 0.20 + 0.30; its z axis points along +x and its x axis down (the URDF writes pi/2 as 1.5708).
  const Eigen::Isometry3d& link6 = poses.at("link6");
  EXPECT_NEAR(link6.translation().x(), 0.38, 1e-9);
  EXPECT_NEAR(link6.translation().y(), 0.0, 1e-9);
  EXPECT_NEAR(link6.translation().z(), 0.60, 1e-9);
  EXPECT_TRUE(link6.rotation().col(2).isApprox(Eigen::Vector3d::UnitX(), 1e-4));
  EXPECT_TRUE(link6.rotation().col(0).isApprox(-Eigen::Vector3d::UnitZ(), 1e-4));
}

TEST(LinkPoses, RevoluteAndMimicJointsMove) {
  SemanticModel model(urdfXml(), srdfXml());
  LinkPoses fk(model.robotModel());
  const LinkPoseMap poses = fk.compute({{"joint1", M_PI / 2}, {"finger1_joint", 0.03}});
  // joint1 turns the whole arm about z: the flange now lies on +y.
  EXPECT_NEAR(poses.at("link6").translation().x(), 0.0, 1e-9);
  EXPECT_NEAR(poses.at("link6").translation().y(), 0.38, 1e-9);
  // The fingers open symmetrically: finger2 mimics finger1 along the opposite palm y axis.
  const Eigen::Vector3d f1 = poses.at("palm").inverse() * poses.at("finger1").translation();
  const Eigen::Vector3d f2 = poses.at("palm").inverse() * poses.at("finger2").translation();
  EXPECT_NEAR(f1.y(), 0.03, 1e-9);
  EXPECT_NEAR(f2.y(), -0.03, 1e-9);
}

// The shared joint-kinds fixture (sixdof_core/test/data): the same limits, groups, order and forward kinematics
// as sixdof_core's and sixdof_sim's test_joint_kinds.
std::string fixtureFile(const std::string& name) {
  return sixdof_core::readTextFile(std::string(SIXDOF_CORE_TEST_DATA_DIR) + "/" + name);
}

TEST(JointKinds, LimitsGroupsAndStatesFollowTheCore) {
  SemanticModel model(fixtureFile("joint_kinds.urdf"), fixtureFile("joint_kinds.srdf"));
  const ActiveJoint* spin = model.activeJoint("spin");
  ASSERT_NE(spin, nullptr);
  EXPECT_FALSE(spin->bounded);
  EXPECT_DOUBLE_EQ(spin->lower, -M_PI);
  EXPECT_DOUBLE_EQ(spin->upper, M_PI);
  const ActiveJoint* lift = model.activeJoint("lift");
  ASSERT_NE(lift, nullptr);
  EXPECT_TRUE(lift->bounded);
  EXPECT_DOUBLE_EQ(lift->upper, 0.3);
  EXPECT_EQ(model.activeJoint("finger_right"), nullptr);  // mimic
  EXPECT_EQ(model.activeJoint("sensor_joint"), nullptr);  // fixed
  ASSERT_NE(model.group("arm"), nullptr);
  EXPECT_EQ(model.group("arm")->joints, (std::vector<std::string>{"spin", "lift", "tilt"}));
  EXPECT_EQ(model.group("arm")->tip_link, "head");
  EXPECT_EQ(model.group("gripper")->joints, std::vector<std::string>{"finger_left"});
  EXPECT_EQ(model.namedStates("gripper"), (std::vector<std::string>{"open", "close"}));
  std::vector<std::string> links;
  for (const auto& link : model.robotModel()->links()) links.push_back(link.name);
  EXPECT_EQ(links, (std::vector<std::string>{"mount", "base_link", "turntable", "carriage", "head", "sensor_frame",
                                             "left_finger", "right_finger"}));
}

TEST(JointKinds, ForwardKinematicsOfEveryKind) {
  SemanticModel model(fixtureFile("joint_kinds.urdf"), fixtureFile("joint_kinds.srdf"));
  LinkPoses fk(model.robotModel());
  EXPECT_EQ(fk.rootLink(), "mount");
  const LinkPoseMap poses = fk.compute({{"spin", M_PI / 2}, {"lift", 0.2}, {"finger_left", 0.03}, {"other", 1.0}});
  EXPECT_TRUE(poses.at("carriage").translation().isApprox(Eigen::Vector3d(0.0, 0.1, 0.45), 1e-12));
  EXPECT_TRUE(poses.at("sensor_frame").translation().isApprox(Eigen::Vector3d(-0.05, 0.1, 0.45), 1e-12));
  const Eigen::Vector3d right = poses.at("head").inverse() * poses.at("right_finger").translation();
  EXPECT_TRUE(right.isApprox(Eigen::Vector3d(0.1, -0.04, 0.0), 1e-12));
}

moveit_msgs::DisplayTrajectory makeTrajectory(const std::vector<double>& times) {
  moveit_msgs::DisplayTrajectory msg;
  msg.trajectory_start.joint_state.name = {"joint1", "joint2"};
  msg.trajectory_start.joint_state.position = {0.5, 0.25};
  moveit_msgs::RobotTrajectory trajectory;
  trajectory.joint_trajectory.joint_names = {"joint1"};
  for (size_t i = 0; i < times.size(); ++i) {
    trajectory_msgs::JointTrajectoryPoint point;
    point.positions = {static_cast<double>(i)};
    point.time_from_start = ros::Duration(times[i]);
    trajectory.joint_trajectory.points.push_back(point);
  }
  msg.trajectory.push_back(trajectory);
  return msg;
}

TEST(TrajectoryStates, MergesStartStateAndConcatenates) {
  moveit_msgs::DisplayTrajectory msg = makeTrajectory({0.0, 1.0, 2.0});
  msg.trajectory.push_back(msg.trajectory.front());
  std::string error;
  auto states = toTrajectoryStates(msg, &error);
  ASSERT_TRUE(states) << error;
  ASSERT_EQ(states->states.size(), 6u);
  EXPECT_DOUBLE_EQ(states->states[1].at("joint1"), 1.0);
  EXPECT_DOUBLE_EQ(states->states[1].at("joint2"), 0.25);  // from trajectory_start
  EXPECT_EQ(states->times, (std::vector<double>{0.0, 1.0, 2.0, 2.0, 3.0, 4.0}));
}

TEST(TrajectoryStates, RejectsMalformedMessages) {
  std::string error;
  EXPECT_FALSE(toTrajectoryStates(makeTrajectory({}), &error));
  EXPECT_EQ(error, "the trajectory has no points");
  auto msg = makeTrajectory({0.0, 1.0});
  msg.trajectory[0].joint_trajectory.points[1].positions.push_back(3.0);
  EXPECT_FALSE(toTrajectoryStates(msg, &error));
  EXPECT_EQ(error, "trajectory 0 point 1 has 2 positions for 1 joints");
  EXPECT_FALSE(toTrajectoryStates(makeTrajectory({1.0, 0.5}), &error));
  EXPECT_EQ(error, "trajectory 0 point 1 goes back in time");
  msg = makeTrajectory({0.0, 1.0});
  msg.trajectory[0].multi_dof_joint_trajectory.joint_names = {"base_joint"};
  EXPECT_FALSE(toTrajectoryStates(msg, &error));
  EXPECT_EQ(error, "trajectory 0 has a multi_dof_joint_trajectory, which is not supported");
  msg = makeTrajectory({0.0, 1.0});
  msg.trajectory_start.multi_dof_joint_state.joint_names = {"base_joint"};
  EXPECT_FALSE(toTrajectoryStates(msg, &error));
  EXPECT_EQ(error, "trajectory_start has multi-DOF joints ('base_joint'), which are not supported");
}

TEST(TrajectoryAnimation, RealtimeFollowsTimeFromStartAndStopsAtEnd) {
  std::string error;
  TrajectoryAnimation animation;
  animation.start(*toTrajectoryStates(makeTrajectory({0.0, 1.0, 2.0}), &error));
  EXPECT_EQ(animation.advance(0.0, false, std::nullopt), 0u);
  EXPECT_EQ(animation.advance(0.5, false, std::nullopt), 0u);
  EXPECT_EQ(animation.advance(0.6, false, std::nullopt), 1u);
  EXPECT_EQ(animation.advance(0.9, false, std::nullopt), 2u);
  EXPECT_FALSE(animation.finished());
  EXPECT_EQ(animation.advance(0.5, false, std::nullopt), 2u);
  EXPECT_TRUE(animation.finished());
  EXPECT_EQ(animation.advance(5.0, false, std::nullopt), 2u);
}

TEST(TrajectoryAnimation, FixedStateTimeAndLoop) {
  std::string error;
  TrajectoryAnimation animation;
  animation.start(*toTrajectoryStates(makeTrajectory({0.0, 10.0, 20.0}), &error));
  EXPECT_EQ(animation.advance(0.15, true, 0.1), 1u);
  EXPECT_EQ(animation.advance(0.1, true, 0.1), 2u);
  EXPECT_EQ(animation.advance(0.1, true, 0.1), 0u);  // past the end: restarts
  EXPECT_FALSE(animation.finished());
  animation.clear();
  EXPECT_FALSE(animation.advance(0.1, true, 0.1));
}

TEST(TrajectoryAnimation, NewTrajectoryWaitsUnlessItInterrupts) {
  std::string error;
  const TrajectoryStates first = *toTrajectoryStates(makeTrajectory({0.0, 1.0}), &error);
  const TrajectoryStates second = *toTrajectoryStates(makeTrajectory({0.0, 1.0, 2.0}), &error);
  TrajectoryAnimation animation;
  EXPECT_TRUE(animation.offer(first, false));  // nothing animating: starts at once
  const unsigned generation = animation.generation();
  EXPECT_EQ(animation.advance(0.5, false, std::nullopt), 0u);
  EXPECT_FALSE(animation.offer(second, false));
  EXPECT_TRUE(animation.hasPending());
  EXPECT_EQ(animation.states().states.size(), 2u);  // still the first one
  EXPECT_EQ(animation.advance(0.6, false, std::nullopt), 0u);  // past the first one's end: the second starts
  EXPECT_EQ(animation.states().states.size(), 3u);
  EXPECT_EQ(animation.generation(), generation + 1);
  EXPECT_FALSE(animation.hasPending());
  EXPECT_TRUE(animation.offer(first, true));  // interrupts
  EXPECT_EQ(animation.states().states.size(), 2u);
}

TEST(TrajectoryAnimation, LoopingTrajectoryGivesWayAfterOneLoop) {
  std::string error;
  TrajectoryAnimation animation;
  animation.offer(*toTrajectoryStates(makeTrajectory({0.0, 1.0}), &error), false);
  EXPECT_EQ(animation.advance(0.5, true, std::nullopt), 0u);
  EXPECT_FALSE(animation.offer(*toTrajectoryStates(makeTrajectory({0.0, 1.0, 2.0}), &error), false));
  EXPECT_EQ(animation.advance(0.6, true, std::nullopt), 0u);
  EXPECT_EQ(animation.states().states.size(), 3u);
}

}  // namespace
}  // namespace sixdof_rviz
