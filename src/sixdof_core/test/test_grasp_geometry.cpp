// The grasp geometry of the fixture grippers (sixdof_test_robots) and the sixdof arm against the dimensions they were
// built with; given values win; what cannot be inferred is a warning, a bad query an error.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sixdof_core/grasp_geometry.h"
#include "sixdof_core/kinematics.h"
#include "test_models.h"

namespace sixdof_core {
namespace {

RobotModelConstPtr gripper(const std::string& file) {
  return std::make_shared<const RobotModel>(readTextFile(std::string(SIXDOF_TEST_ROBOTS_DIR) + "/urdf/" + file), "");
}

// Every moving joint of a model below its root.
GripperQuery everything(const RobotModel& model) {
  GripperQuery query;
  query.parent_link = model.rootLink();
  for (const auto& joint : model.joints()) {
    if (joint.type != JointType::kFixed) query.joints.push_back(joint.name);
  }
  return query;
}

TEST(GraspGeometry, PrismaticFingers) {
  const auto model = gripper("parallel_hand.urdf");
  const GraspGeometry g = analyzeGripper(model, everything(*model));
  // Pads 5.5 cm long from the palm face 5 cm into the hand, their inner faces at +-finger position.
  EXPECT_TRUE(g.tcp.translation().isApprox(Eigen::Vector3d(0, 0, 0.0775), 1e-12)) << g.tcp.translation();
  EXPECT_TRUE(g.tcp.linear().isIdentity(1e-12));
  EXPECT_EQ(g.tcp_source, "pads");
  EXPECT_EQ(g.pad_links, (std::vector<std::string>{"right_finger", "left_finger"}));
  EXPECT_EQ(g.open, (std::map<std::string, double>{{"left_finger_joint", 0.04}}));  // no mimic joint
  EXPECT_EQ(g.closed, (std::map<std::string, double>{{"left_finger_joint", 0.0}}));
  EXPECT_NEAR(g.open_width, 0.08, 1e-12);
  EXPECT_NEAR(g.closed_width, 0.0, 1e-12);
  EXPECT_NEAR(g.reach, 0.0275, 1e-12);
  EXPECT_NEAR(g.palm_depth, 0.0275, 1e-12);
  EXPECT_TRUE(g.closing_direction.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(g.warnings.empty());
}

TEST(GraspGeometry, RevoluteJawsOpenAtTheirUpperLimit) {
  const auto model = gripper("jaw_gripper.urdf");
  const GraspGeometry g = analyzeGripper(model, everything(*model));
  ASSERT_EQ(g.finger_joints.size(), 1u);
  EXPECT_GT(g.finger_joints[0].width_at_upper, g.finger_joints[0].width_at_lower);
  EXPECT_EQ(g.open.at("left_jaw_joint"), 0.3);
  EXPECT_EQ(g.closed.at("left_jaw_joint"), -0.45);
  // Half closed (-0.075 rad) the jaws meet an object at their tips: 7.5 cm below their joints 5 cm into the palm.
  EXPECT_NEAR(g.tcp.translation().z(), 0.05 + 0.075 * std::cos(0.075), 1e-9);
  EXPECT_NEAR(g.open_width, 0.08, 1e-9);  // the inner faces at the joints, 4 cm either side
  // A tip's outer edge (1.2 cm across, 7.5 cm down) reaches furthest at atan(0.012 / 0.075) = 0.16 rad, between
  // open and closed (sampled in steps of 0.015 rad).
  EXPECT_NEAR(g.reach, 0.05 + std::hypot(0.012, 0.075) - g.tcp.translation().z(), 1e-5);
}

TEST(GraspGeometry, AMimicLinkageClosingTowardsItsUpperLimit) {
  const auto model = gripper("adaptive_gripper.urdf");
  const GraspGeometry g = analyzeGripper(model, everything(*model));
  EXPECT_EQ(g.open.at("finger_joint"), 0.0);
  EXPECT_EQ(g.closed.at("finger_joint"), 0.8);
  EXPECT_EQ(g.open.size(), 1u);
  EXPECT_EQ(g.pad_links, (std::vector<std::string>{"right_inner_finger", "left_inner_finger"}));
  EXPECT_EQ(g.finger_links.size(), 6u);
  // Knuckles of 5.5 cm jointed 6 cm into the base, tilted -0.35 + 0.4 rad half closed; pads 4 cm below them.
  EXPECT_TRUE(g.tcp.translation().isApprox(Eigen::Vector3d(0, 0, 0.06 + 0.055 * std::cos(0.05) + 0.02), 1e-9))
      << g.tcp.translation();
  EXPECT_TRUE(g.tcp.linear().isIdentity(1e-9));
  EXPECT_NEAR(g.open_width, 2 * (0.0239 + 0.055 * std::sin(0.35)), 1e-9);
  EXPECT_NEAR(g.closed_width, 2 * (0.0239 - 0.055 * std::sin(0.45)), 1e-9);
  // The pads reach furthest with the knuckles upright (0.35 rad, between open and closed): 3.3 mm beyond the
  // open state's reach.
  EXPECT_NEAR(g.reach, 0.06 + 0.055 + 0.04 - g.tcp.translation().z(), 1e-6);
}

TEST(GraspGeometry, ALinkNamedTcpWinsAndGivenValuesOverrideInference) {
  const auto model = armModel();
  GripperQuery query;
  query.parent_link = "link6";
  query.joints = {"finger1_joint", "finger2_joint"};
  GraspGeometry g = analyzeGripper(model, query);
  EXPECT_EQ(g.tcp_source, "link 'tcp'");
  RobotState state(model);
  EXPECT_TRUE(g.tcp.isApprox(state.linkTransform("link6").inverse() * state.linkTransform("tcp")));
  EXPECT_NEAR(g.open_width, 0.08, 1e-9);

  query.tcp_link = "no_such_link";  // as for a robot without a tcp link
  query.open = {{"finger1_joint", 0.03}};
  query.pad_links = {"finger1", "finger2"};
  query.closing_direction = Eigen::Vector3d(0, -2, 0);
  query.tcp = poseFromXyzRpy(0, 0, 0.1, 0, 0, 0);
  query.tcp_parent = "palm";
  g = analyzeGripper(model, query);
  EXPECT_EQ(g.tcp_source, "given");
  EXPECT_TRUE(g.tcp.isApprox(state.linkTransform("link6").inverse() * state.linkTransform("palm") * *query.tcp));
  EXPECT_EQ(g.open.at("finger1_joint"), 0.03);
  EXPECT_NEAR(g.open_width, 0.06, 1e-9);
  EXPECT_TRUE(g.closing_direction.isApprox(Eigen::Vector3d::UnitY()));  // the TCP's y, which the given axis spans
}

TEST(GraspGeometry, WhatCannotBeInferredIsAWarning) {
  // One finger: nothing on the other side of the closing direction.
  const auto one = std::make_shared<const RobotModel>(R"(<robot name="one"><link name="palm"/>
      <link name="finger"><collision><geometry><box size="0.01 0.01 0.05"/></geometry></collision></link>
      <joint name="slide" type="prismatic"><parent link="palm"/><child link="finger"/><axis xyz="0 1 0"/>
        <limit lower="0" upper="0.04" effort="1" velocity="1"/></joint></robot>)",
                                                      "");
  GripperQuery query;
  query.parent_link = "palm";
  query.joints = {"slide"};
  const GraspGeometry g = analyzeGripper(one, query);
  EXPECT_EQ(g.tcp_source, "parent link");
  EXPECT_TRUE(g.tcp.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(g.pad_links.empty());
  EXPECT_EQ(g.open.at("slide"), 0.04);  // the upper limit, without pads
  EXPECT_GE(g.warnings.size(), 2u);
}

TEST(GraspGeometry, BadQueriesAreNamed) {
  const auto model = armModel();
  const auto error = [&](const GripperQuery& query) {
    try {
      analyzeGripper(model, query);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  GripperQuery good;
  good.parent_link = "link6";
  good.joints = {"finger1_joint", "finger2_joint"};
  GripperQuery q = good;
  q.parent_link = "nope";
  EXPECT_NE(error(q).find("'nope'"), std::string::npos);
  q = good;
  q.joints = {"palm_joint"};
  EXPECT_NE(error(q).find("fixed"), std::string::npos);
  q.joints = {"finger2_joint"};
  EXPECT_NE(error(q).find("actuated"), std::string::npos);
  q = good;
  q.tcp = Eigen::Isometry3d::Identity();
  EXPECT_NE(error(q).find("link named 'tcp'"), std::string::npos);
  q = good;
  q.closed = {{"finger1_joint", 0.5}};
  EXPECT_NE(error(q).find("outside its limits"), std::string::npos);
  q = good;
  q.open = {{"joint1", 0.0}};
  EXPECT_NE(error(q).find("'joint1'"), std::string::npos);
  q = good;
  q.pad_links = {"finger1"};
  EXPECT_NE(error(q).find("two different pad links"), std::string::npos);
  q.pad_links = {"finger1", "no_pad"};
  EXPECT_NE(error(q).find("'no_pad'"), std::string::npos);
  q = good;
  q.closing_direction = Eigen::Vector3d::Zero();
  EXPECT_NE(error(q).find("zero"), std::string::npos);
  q = good;
  q.tcp_link = "no_such_link";
  q.tcp = Eigen::Isometry3d::Identity();
  q.tcp_parent = "finger1";
  EXPECT_NE(error(q).find("moved by joint 'finger1_joint'"), std::string::npos);
}

}  // namespace
}  // namespace sixdof_core
