// Every joint kind on one fixture (test/data/joint_kinds.urdf/.srdf), as the core model reads it. The same
// fixture and the same expectations are tested in sixdof_sim (test_joint_kinds), sixdof_rviz (test_logic_core)
// and sixdof_scripts (the robot-model query): docs/design.md "One robot model".

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/robot_model.h"
#include "test_models.h"

namespace sixdof_core {
namespace {

RobotModelConstPtr fixture() {
  return RobotModel::fromFiles(kDataDir + "/joint_kinds.urdf", kDataDir + "/joint_kinds.srdf");
}

std::vector<std::string> linkNames(const RobotModel& model) {
  std::vector<std::string> names;
  for (const auto& link : model.links()) names.push_back(link.name);
  return names;
}

TEST(JointKinds, LinksBreadthFirstInDocumentOrder) {
  const auto model = fixture();
  EXPECT_EQ(model->rootLink(), "mount");
  EXPECT_EQ(linkNames(*model), (std::vector<std::string>{"mount", "base_link", "turntable", "carriage", "head",
                                                         "sensor_frame", "left_finger", "right_finger"}));
  for (size_t i = 1; i < model->links().size(); ++i) {
    EXPECT_EQ(model->joints()[i - 1].child_link, model->links()[i].name);
  }
}

TEST(JointKinds, VariablesAreActiveJointsWithoutMimic) {
  const auto model = fixture();
  EXPECT_EQ(model->variableNames(), (std::vector<std::string>{"spin", "lift", "tilt", "finger_left"}));
  EXPECT_FALSE(model->joint("finger_right").isActive());
  ASSERT_TRUE(model->joint("finger_right").mimic.has_value());
  EXPECT_EQ(model->joint("finger_right").mimic->joint, "finger_left");
  EXPECT_DOUBLE_EQ(model->joint("finger_right").mimic->multiplier, 1.0);
}

TEST(JointKinds, ContinuousIsUnboundedWithNominalPlusMinusPi) {
  const auto model = fixture();
  const JointModel& spin = model->joint("spin");
  EXPECT_EQ(spin.type, JointType::kContinuous);
  EXPECT_FALSE(spin.limits.bounded);
  EXPECT_DOUBLE_EQ(spin.limits.lower, -M_PI);
  EXPECT_DOUBLE_EQ(spin.limits.upper, M_PI);
  EXPECT_DOUBLE_EQ(spin.limits.velocity, 2.0);
  EXPECT_DOUBLE_EQ(spin.damping, 0.1);
  const JointModel& lift = model->joint("lift");
  EXPECT_EQ(lift.type, JointType::kPrismatic);
  EXPECT_TRUE(lift.limits.bounded);
  EXPECT_DOUBLE_EQ(lift.limits.lower, 0.0);
  EXPECT_DOUBLE_EQ(lift.limits.upper, 0.3);
  // A continuous joint beyond pi is within bounds; a prismatic one beyond its limit is not.
  expectBoundsCheck(model, "spin", 4.0, "lift", 0.31);
}

TEST(JointKinds, LinksWithoutGeometryOrInertia) {
  const auto model = fixture();
  EXPECT_TRUE(model->link("mount").collision.shapes.empty());
  EXPECT_FALSE(model->link("mount").inertial.has_value());
  EXPECT_TRUE(model->link("sensor_frame").collision.shapes.empty());
  EXPECT_FALSE(model->link("sensor_frame").inertial.has_value());
  EXPECT_TRUE(model->link("mount").visuals.empty());
  // Visuals with their material colour (a named material of the robot); links without visuals have none.
  ASSERT_EQ(model->link("base_link").visuals.size(), 1u);
  ASSERT_TRUE(model->link("base_link").visuals[0].rgba.has_value());
  EXPECT_TRUE(model->link("base_link").visuals[0].rgba->isApprox(Eigen::Vector4d(0, 0, 1, 1)));
  EXPECT_TRUE(model->link("head").visuals.empty());
  ASSERT_TRUE(model->link("head").inertial.has_value());
  EXPECT_DOUBLE_EQ(model->link("head").inertial->mass, 0.3);
  EXPECT_TRUE(model->link("head").inertial->origin.translation().isApprox(Eigen::Vector3d(0.05, 0, 0)));
}

TEST(JointKinds, ForwardKinematicsOfEveryKind) {
  const auto model = fixture();
  RobotState state(model);
  state.setJointPosition("spin", M_PI / 2);
  state.setJointPosition("lift", 0.2);
  state.setJointPosition("finger_left", 0.03);
  // carriage: mount -> +0.1 z, spin origin +0.1 z, then lift origin (0.1, 0, 0.05) rotated by 90 deg about z.
  EXPECT_TRUE(state.linkTransform("carriage").translation().isApprox(Eigen::Vector3d(0.0, 0.1, 0.45), 1e-12));
  EXPECT_TRUE(state.linkTransform("sensor_frame").translation().isApprox(Eigen::Vector3d(-0.05, 0.1, 0.45), 1e-12));
  // The mimic finger moves with its master, along its own (-y) axis.
  EXPECT_DOUBLE_EQ(state.jointPosition("finger_right"), 0.03);
  const Eigen::Vector3d left = state.linkTransform("head").inverse() * state.linkTransform("left_finger").translation();
  const Eigen::Vector3d right =
      state.linkTransform("head").inverse() * state.linkTransform("right_finger").translation();
  EXPECT_TRUE(left.isApprox(Eigen::Vector3d(0.1, 0.04, 0.0), 1e-12));
  EXPECT_TRUE(right.isApprox(Eigen::Vector3d(0.1, -0.04, 0.0), 1e-12));
}

TEST(JointKinds, GroupsStatesAndEndEffector) {
  const auto model = fixture();
  const JointGroup* arm = model->findGroup("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_EQ(arm->active_joints, (std::vector<std::string>{"spin", "lift", "tilt"}));
  const JointGroup* gripper = model->findGroup("gripper");
  ASSERT_NE(gripper, nullptr);
  EXPECT_EQ(gripper->active_joints, (std::vector<std::string>{"finger_left"}));
  EXPECT_EQ(gripper->joints, (std::vector<std::string>{"finger_left", "finger_right"}));
  ASSERT_NE(model->findGroupState("gripper", "open"), nullptr);
  ASSERT_EQ(model->endEffectors().size(), 1u);
  EXPECT_EQ(model->endEffectors()[0].parent_link, "head");
  const KinematicChain chain = KinematicChain::forGroup(*model, "arm");
  EXPECT_EQ(chain.jointNames(), arm->active_joints);
}

TEST(JointKinds, WithoutSrdfTheModelHasNoSemantics) {
  const RobotModel model(readTextFile(kDataDir + "/joint_kinds.urdf"), "");
  EXPECT_EQ(model.variableCount(), 4u);
  EXPECT_TRUE(model.groups().empty());
}

}  // namespace
}  // namespace sixdof_core
