// Joint limits from the URDF and joint_limits.yaml (the sixdof arm's description).
#include <gtest/gtest.h>

#include "test_helpers.h"

namespace sixdof_control {
namespace {

using test::sixdofModel;

TEST(JointLimits, UrdfLimitsOverriddenByJointLimitsYaml) {
  const auto limits = loadJointLimits(
      *sixdofModel(), YAML::LoadFile(SIXDOF_DESCRIPTION_DIR "/config/joint_limits.yaml"), {"joint2", "finger1_joint"});
  ASSERT_EQ(limits.size(), 2u);
  EXPECT_EQ(limits[0].joint, "joint2");
  EXPECT_TRUE(limits[0].has_position_limits);
  EXPECT_DOUBLE_EQ(limits[0].min_position, sixdofModel()->joint("joint2").limits.lower);
  EXPECT_DOUBLE_EQ(limits[0].max_position, sixdofModel()->joint("joint2").limits.upper);
  EXPECT_TRUE(limits[0].has_velocity_limits);
  EXPECT_DOUBLE_EQ(limits[0].max_velocity, 2.0);
  EXPECT_DOUBLE_EQ(limits[1].max_velocity, 0.1);

  const auto tighter = loadJointLimits(
      *sixdofModel(),
      YAML::Load("joint_limits: {joint2: {has_position_limits: true, min_position: -1, max_position: 0.5, "
                 "has_velocity_limits: true, max_velocity: 0.7}}"),
      {"joint2"});
  EXPECT_DOUBLE_EQ(tighter[0].min_position, -1.0);
  EXPECT_DOUBLE_EQ(tighter[0].max_position, 0.5);
  EXPECT_DOUBLE_EQ(tighter[0].max_velocity, 0.7);
  // Without a file: the URDF's.
  EXPECT_DOUBLE_EQ(loadJointLimits(*sixdofModel(), YAML::Node(), {"joint2"})[0].max_velocity,
                   sixdofModel()->joint("joint2").limits.velocity);
}

TEST(JointLimits, BadEntriesAreNamed) {
  const auto problem = [](const std::string& yaml, const std::string& joint = "joint2") {
    try {
      loadJointLimits(*sixdofModel(), YAML::Load(yaml), {joint});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(problem("joint_limits: {joint2: {max_velocty: 1}}").find("max_velocty"), std::string::npos);
  EXPECT_NE(problem("joint_limits: {joint2: {has_velocity_limits: true, max_velocity: fast}}").find("max_velocity"),
            std::string::npos);
  EXPECT_NE(problem("joint_limits: {joint2: {has_velocity_limits: true, max_velocity: 0}}").find("not > 0"),
            std::string::npos);
  EXPECT_NE(problem("joint_limits: {joint2: {has_position_limits: true, min_position: 1, max_position: 0}}")
                .find("min_position above max_position"),
            std::string::npos);
  EXPECT_NE(problem("{}", "knee").find("'knee'"), std::string::npos);
}

}  // namespace
}  // namespace sixdof_control
