// Every joint kind on the shared fixture (sixdof_core/test/data/joint_kinds.urdf), as the simulator builds it
// from the core robot model: the same link and joint order, the same limit convention and the same forward
// kinematics as sixdof_core's test_joint_kinds; the one-line error for a link it cannot simulate.

#include <gtest/gtest.h>

#include <cmath>

#include "sixdof_sim/urdf_loader.h"
#include "sixdof_sim/world.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

std::string fixtureUrdf() { return test::readFile(std::string(SIXDOF_CORE_TEST_DATA_DIR) + "/joint_kinds.urdf"); }

World makeWorld(const std::string& urdf) {
  WorldSpec empty;
  empty.ground.enabled = false;
  WorldOptions options;
  options.grasp_fix_enabled = false;
  return World(urdf, empty, options);
}

TEST(JointKinds, SameOrderAsTheCoreModel) {
  const World world = makeWorld(fixtureUrdf());
  EXPECT_EQ(world.linkNames(), (std::vector<std::string>{"mount", "base_link", "turntable", "carriage", "head",
                                                         "sensor_frame", "left_finger", "right_finger"}));
  // Every moving joint is simulated, the mimic finger included (it has a body of its own).
  EXPECT_EQ(world.jointNames(), (std::vector<std::string>{"spin", "lift", "tilt", "finger_left", "finger_right"}));
}

TEST(JointKinds, ContinuousJointIsUnboundedOthersAreNot) {
  World world = makeWorld(fixtureUrdf());
  const JointInfo& spin = world.joints()[world.jointIndex("spin")];
  EXPECT_FALSE(spin.bounded);
  EXPECT_DOUBLE_EQ(spin.lower, -M_PI);
  EXPECT_DOUBLE_EQ(spin.upper, M_PI);
  const JointInfo& lift = world.joints()[world.jointIndex("lift")];
  EXPECT_TRUE(lift.bounded);
  EXPECT_EQ(lift.type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(lift.upper, 0.3);
  EXPECT_TRUE(world.setPositionTarget("spin", 4.0).ok());
  EXPECT_TRUE(world.setJointPositions({"spin"}, {-4.0}).ok());
  EXPECT_EQ(world.setJointPositions({"lift"}, {0.31}).status, Status::kOutOfLimits);
  EXPECT_EQ(world.setPositionTarget("finger_right", 0.01).status, Status::kMimicJoint);
}

TEST(JointKinds, ForwardKinematicsMatchesTheCore) {
  World world = makeWorld(fixtureUrdf());
  ASSERT_TRUE(world.setJointPositions({"spin", "lift", "finger_left"}, {M_PI / 2, 0.2, 0.03}).ok());
  EXPECT_TRUE(test::linkPose(world, "carriage").translation().isApprox(Eigen::Vector3d(0.0, 0.1, 0.45), 1e-9));
  EXPECT_TRUE(test::linkPose(world, "sensor_frame").translation().isApprox(Eigen::Vector3d(-0.05, 0.1, 0.45), 1e-9));
  EXPECT_NEAR(world.jointPositions()[world.jointIndex("finger_right")], 0.03, 1e-9);
  const Eigen::Isometry3d head = test::linkPose(world, "head");
  EXPECT_TRUE((head.inverse() * test::linkPose(world, "left_finger").translation())
                  .isApprox(Eigen::Vector3d(0.1, 0.04, 0.0), 1e-9));
  EXPECT_TRUE((head.inverse() * test::linkPose(world, "right_finger").translation())
                  .isApprox(Eigen::Vector3d(0.1, -0.04, 0.0), 1e-9));
}

TEST(JointKinds, MovingLinkWithoutInertiaIsOneLineNamingIt) {
  std::string urdf = fixtureUrdf();
  const std::string head_inertial = "<inertial><origin xyz=\"0.05 0 0\"/><mass value=\"0.3\"/>";
  const size_t at = urdf.find(head_inertial);
  ASSERT_NE(at, std::string::npos);
  const size_t end = urdf.find("</inertial>", at) + std::string("</inertial>").size();
  urdf.erase(at, end - at);
  try {
    makeWorld(urdf);
    ADD_FAILURE() << "no error for a moving link without inertia";
  } catch (const WorldError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("link 'head' cannot be simulated"), std::string::npos) << message;
    EXPECT_NE(message.find("'tilt'"), std::string::npos) << message;
    EXPECT_NE(message.find("setup_assistant"), std::string::npos) << "the fix is not named: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace sixdof_sim
