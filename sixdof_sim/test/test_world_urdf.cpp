// URDF loading: merged fixed links, principal-axis inertias, <gazebo><mu1>, errors; gentle contacts.

#include <gtest/gtest.h>

#include "sixdof_sim/urdf_loader.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

// A two-link arm with a tilted, off-diagonal inertia, a fixed tool and friction extensions.
const char* const kArm = R"(<?xml version="1.0"?>
<robot name="two_link">
  <link name="base"/>
  <link name="upper">
    <inertial><origin xyz="0 0 0.2" rpy="0.3 0.2 0.1"/><mass value="1.5"/>
      <inertia ixx="0.02" ixy="0.003" ixz="-0.001" iyy="0.015" iyz="0.002" izz="0.004"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></collision>
  </link>
  <link name="tool">
    <inertial><origin xyz="0 0 0.02"/><mass value="0.2"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><geometry><box size="0.04 0.04 0.04"/></geometry></collision>
  </link>
  <link name="tip"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="50" velocity="1"/>
    <dynamics damping="0.3" friction="0.05"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0 0 0.4"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="tool"/><child link="tip"/><origin xyz="0 0 0.05"/></joint>
  <gazebo reference="tool"><mu1>0.6</mu1><mu2>0.6</mu2></gazebo>
</robot>)";

TEST(UrdfLoader, ReadsJointsInertiasAndFriction) {
  const RobotDescription d = parseRobotDescription(kArm);
  EXPECT_EQ(d.name, "two_link");
  EXPECT_EQ(d.root_link, "base");
  ASSERT_EQ(d.links.size(), 4u);
  ASSERT_EQ(d.joints.size(), 3u);
  EXPECT_EQ(d.joints[0].info.child_link, d.links[1].name);
  EXPECT_FALSE(d.joints[0].fixed);
  EXPECT_TRUE(d.joints[1].fixed);
  EXPECT_DOUBLE_EQ(d.joints[0].info.damping, 0.3);
  EXPECT_DOUBLE_EQ(d.joints[0].info.friction, 0.05);
  EXPECT_DOUBLE_EQ(d.joints[0].info.max_effort, 50.0);
  // The inertia is rotated from the inertial frame into the link frame (same eigenvalues).
  const RobotLink& upper = d.links[1];
  Eigen::Matrix3d original;
  original << 0.02, 0.003, -0.001, 0.003, 0.015, 0.002, -0.001, 0.002, 0.004;
  const Eigen::Vector3d expected = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(original).eigenvalues();
  const Eigen::Vector3d got = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(upper.inertia).eigenvalues();
  EXPECT_TRUE(got.isApprox(expected, 1e-12));
  EXPECT_FALSE(upper.inertia.isApprox(original));
  EXPECT_TRUE(upper.com.isApprox(Eigen::Vector3d(0, 0, 0.2)));
  ASSERT_TRUE(d.links[2].friction.has_value());
  EXPECT_DOUBLE_EQ(*d.links[2].friction, 0.6);
  EXPECT_FALSE(d.links[1].friction.has_value());
  EXPECT_FALSE(d.grasp_fix.has_value());
}

std::string errorOf(const std::string& urdf) {
  return test::errorMessage<std::invalid_argument>([&] { parseRobotDescription(urdf); });
}

TEST(UrdfLoader, ErrorsNameTheProblem) {
  std::string text = kArm;
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  EXPECT_NE(errorOf(with("<mu1>0.6</mu1>", "<mu1>slippery</mu1>")).find("<mu1>"), std::string::npos);
  EXPECT_NE(errorOf(with("reference=\"tool\"", "reference=\"hand\"")).find("reference=\"hand\">: no such link"),
            std::string::npos);
  EXPECT_NE(errorOf(with("effort=\"50\"", "effort=\"0\"")).find("'shoulder'"), std::string::npos);
  EXPECT_NE(errorOf(with("<mass value=\"1.5\"/>", "<mass value=\"0\"/>")).find("'upper'"), std::string::npos);
  EXPECT_NE(errorOf("<robot"), "");
}

TEST(UrdfLoader, FixedChildrenMergeIntoOneBody) {
  // The merged upper+tool body swings under gravity as one pendulum; tip follows rigidly.
  WorldSpec empty;
  empty.ground.enabled = false;
  WorldOptions options;
  options.grasp_fix_enabled = false;
  World world(kArm, empty, options);
  EXPECT_EQ(world.jointNames(), std::vector<std::string>{"shoulder"});
  EXPECT_EQ(world.linkNames(), (std::vector<std::string>{"base", "upper", "tool", "tip"}));
  ASSERT_TRUE(world.setJointPositions({"shoulder"}, {0.5}).ok());
  const Eigen::Isometry3d tip = test::linkPose(world, "tip");
  // Rotation about +y by 0.5 of the point (0, 0, 0.45) above the shoulder at height 0.1.
  const Eigen::Vector3d expected(0.45 * std::sin(0.5), 0.0, 0.1 + 0.45 * std::cos(0.5));
  EXPECT_TRUE(tip.translation().isApprox(expected, 1e-12));
  ASSERT_TRUE(world.setEffort("shoulder", 0.0).ok());
  world.step(300);
  EXPECT_GT(world.jointPositions()[0], 0.6);  // falls further away from upright
  const Eigen::Isometry3d tool = test::linkPose(world, "tool");
  EXPECT_NEAR((tool.inverse() * test::linkPose(world, "tip")).translation().z(), 0.05, 1e-9);
}

// An object spawned 5 mm into the table is pushed out gently: no launch.
TEST(Contacts, PenetrationIsResolvedWithoutLaunchingTheObject) {
  World world(test::robotUrdf(), loadWorldFile(test::defaultWorldPath()), test::options(false));
  ObjectSpec cube;
  cube.name = "sunk";
  cube.shape.box_size = Eigen::Vector3d::Constant(0.04);
  cube.pose.translation() = Eigen::Vector3d(0.3, 0.3, 0.015);
  ASSERT_TRUE(world.spawnObject(cube).ok());
  double max_speed = 0.0;
  double max_z = 0.0;
  for (int i = 0; i < 1000; ++i) {
    world.step();
    ObjectState state;
    ASSERT_TRUE(world.objectState("sunk", &state).ok());
    max_speed = std::max(max_speed, state.twist.linear.norm());
    max_z = std::max(max_z, state.spec.pose.translation().z());
  }
  EXPECT_LT(max_speed, 0.12);
  EXPECT_LT(max_z, 0.021);  // never jumps more than 1 mm above its resting height
  ObjectState state;
  ASSERT_TRUE(world.objectState("sunk", &state).ok());
  EXPECT_NEAR(state.spec.pose.translation().z(), 0.02, 1.5e-3);
}

}  // namespace
}  // namespace sixdof_sim
