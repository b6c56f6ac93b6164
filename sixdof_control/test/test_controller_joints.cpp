// ControllerJoints: a controller with a mimic joint (the sixdof arm's fingers) mapped to its actuated joints and
// back, as the driver node does.
#include <gtest/gtest.h>

#include <stdexcept>

#include "sixdof_control/controller_joints.h"

namespace sixdof_control {
namespace {

using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryGoal;

std::vector<RobotJoint> robot() {
  RobotJoint finger1{"finger1", true, 0.0, 0.04, 40.0, "", 1.0, 0.0};
  RobotJoint finger2{"finger2", true, 0.0, 0.04, 40.0, "finger1", 2.0, 0.01};
  RobotJoint wrist{"wrist", false, -3.14, 3.14, 10.0, "", 1.0, 0.0};
  return {wrist, finger1, finger2};
}

TrajectoryGoal goal(const std::vector<std::string>& names, const std::vector<double>& positions) {
  TrajectoryGoal g;
  g.joint_names = names;
  g.points.push_back({positions, std::vector<double>(positions.size(), 0.0), {}, 1.0});
  return g;
}

TEST(ControllerJoints, MapsMimicJointsToTheirMasters) {
  const ControllerJoints joints("gripper", {"finger2", "finger1"}, robot());
  EXPECT_EQ(joints.actuated(), std::vector<std::string>{"finger1"});
  EXPECT_TRUE(joints.hasMimics());
  EXPECT_EQ(joints.checkMimics(goal({"finger1", "finger2"}, {0.01, 0.03})), "");
  EXPECT_NE(joints.checkMimics(goal({"finger1", "finger2"}, {0.01, 0.02})).find("mimics 'finger1'"), std::string::npos);
  // A goal that leaves a joint out passes the mimic check (the controller refuses it) but cannot be mapped.
  EXPECT_EQ(joints.checkMimics(goal({"finger1"}, {0.01})), "");
  TrajectoryGoal actuated;
  EXPECT_EQ(joints.actuatedGoal(goal({"finger1"}, {0.01}), actuated).status, TrajectoryErrorCode::kInvalidJoints);
  ASSERT_TRUE(joints.actuatedGoal(goal({"finger1", "finger2"}, {0.01, 0.03}), actuated).ok());
  EXPECT_EQ(actuated.joint_names, std::vector<std::string>{"finger1"});
  EXPECT_EQ(actuated.points[0].positions, std::vector<double>{0.01});
  EXPECT_EQ(actuated.points[0].velocities, std::vector<double>{0.0});
  TrajectoryGoal short_velocities = goal({"finger1", "finger2"}, {0.01, 0.03});
  short_velocities.points[0].velocities = {0.0};
  EXPECT_EQ(joints.actuatedGoal(short_velocities, actuated).status, TrajectoryErrorCode::kInvalidGoal);
  // Back on every joint, in the controller's order: finger2 = 2 finger1 + 0.01 (no offset on derivatives).
  const sixdof_core::TrajectorySample sample = joints.expand({{0.01}, {0.1}, {1.0}});
  EXPECT_EQ(sample.position, (std::vector<double>{0.03, 0.01}));
  EXPECT_EQ(sample.velocity, (std::vector<double>{0.2, 0.1}));
  EXPECT_EQ(sample.acceleration, (std::vector<double>{2.0, 1.0}));
  EXPECT_EQ(joints.expand({{0.01}, {}, {}}, false).position, (std::vector<double>{0.02, 0.01}));
}

TEST(ControllerJoints, ActuatedConfigDropsTheMimicJoints) {
  const ControllerJoints joints("gripper", {"finger1", "finger2"}, robot());
  sixdof_core::TrajectoryControllerConfig config;
  config.name = "gripper";
  config.joints = {"finger1", "finger2"};
  config.lower_limits = {0.0, 0.0};
  config.upper_limits = {0.04, 0.09};
  config.path_tolerance = {0.1, 0.2};
  config.goal_tolerance = {0.01, 0.02};
  const sixdof_core::TrajectoryControllerConfig out = joints.actuatedConfig(config);
  EXPECT_EQ(out.joints, std::vector<std::string>{"finger1"});
  EXPECT_EQ(out.upper_limits, std::vector<double>{0.04});
  EXPECT_EQ(out.goal_tolerance, std::vector<double>{0.01});
}

TEST(ControllerJoints, RefusesUnknownJointsAndMastersOutsideTheController) {
  EXPECT_THROW(ControllerJoints("arm", {"elbow"}, robot()), std::invalid_argument);
  EXPECT_THROW(ControllerJoints("gripper", {"finger2"}, robot()), std::invalid_argument);
  const ControllerJoints plain("arm", {"wrist"}, robot());
  EXPECT_FALSE(plain.hasMimics());
}

}  // namespace
}  // namespace sixdof_control
