#pragma once
// Shared by the control tests: the sixdof arm's joints and limits, and a simulated-time driver of the loop.

#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <vector>

#include "sixdof_control/control_loop.h"
#include "sixdof_control/joint_limits.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_control::test {

inline std::shared_ptr<const sixdof_core::RobotModel> sixdofModel() {
  static const auto model = std::make_shared<const sixdof_core::RobotModel>(
      sixdof_core::readTextFile(SIXDOF_DESCRIPTION_DIR "/urdf/sixdof.urdf"), "",
      sixdof_core::PackageResolver::fromMap({{"sixdof_description", SIXDOF_DESCRIPTION_DIR}}));
  return model;
}

inline std::vector<std::string> armJoints() { return {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"}; }

// The arm's controller as controllers.yaml has it (tolerances), its joints' limits from the description.
inline ControlLoopConfig armLoopConfig() {
  ControlLoopConfig c;
  c.joints = armJoints();
  c.limits =
      loadJointLimits(*sixdofModel(), YAML::LoadFile(SIXDOF_DESCRIPTION_DIR "/config/joint_limits.yaml"), c.joints);
  sixdof_core::TrajectoryControllerConfig arm;
  arm.name = "arm_controller";
  arm.joints = c.joints;
  arm.path_tolerance.assign(6, 0.2);
  arm.goal_tolerance.assign(6, 0.01);
  arm.goal_time = 0.6;
  arm.stopped_velocity_tolerance = 0.05;
  c.controllers = {arm};
  return c;
}

// The arm's controller plus the first finger's: a trajectory controller and a gripper_cmd controller on one joint.
inline ControlLoopConfig armAndGripperConfig() {
  ControlLoopConfig c = armLoopConfig();
  c.joints.push_back("finger1_joint");
  c.limits =
      loadJointLimits(*sixdofModel(), YAML::LoadFile(SIXDOF_DESCRIPTION_DIR "/config/joint_limits.yaml"), c.joints);
  sixdof_core::TrajectoryControllerConfig fingers;
  fingers.name = "gripper_controller";
  fingers.joints = {"finger1_joint"};
  fingers.path_tolerance = {0.0};
  fingers.goal_tolerance = {0.002};
  fingers.goal_time = 0.6;
  fingers.stopped_velocity_tolerance = 0.05;
  c.controllers.push_back(fingers);
  sixdof_core::GripperControllerConfig gripper;
  gripper.name = "gripper_controller";
  gripper.joint = "finger1_joint";
  gripper.effort_limit = sixdofModel()->joint("finger1_joint").limits.effort;
  gripper.goal_tolerance = 0.002;
  c.grippers = {gripper};
  return c;
}

// A goal through the given points (positions, time) of every arm joint, at rest at each (cubic segments).
inline sixdof_core::TrajectoryGoal armGoal(const std::vector<std::pair<std::vector<double>, double>>& points) {
  sixdof_core::TrajectoryGoal g;
  g.joint_names = armJoints();
  for (const auto& [q, t] : points) g.points.push_back({q, std::vector<double>(q.size(), 0.0), {}, t});
  return g;
}

}  // namespace sixdof_control::test
