#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "sixdof_core/robot_model.h"

namespace sixdof_control {

// The limits the control loop enforces on every command of one joint.
struct JointLimit {
  std::string joint;
  bool has_position_limits = false;
  double min_position = 0.0;
  double max_position = 0.0;
  bool has_velocity_limits = false;
  double max_velocity = 0.0;  // > 0 when has_velocity_limits
};

// The limits of `joints` as MoveIt takes them: the URDF's (position limits unless the joint is continuous, the
// velocity limit when positive), overridden by joint_limits.yaml (`joint_limits: {<joint>: {has_position_limits,
// min_position, max_position, has_velocity_limits, max_velocity, has_acceleration_limits, max_acceleration}}`)
// where it sets them. `joint_limits` is the parsed file (a null node: the URDF's only). Throws
// std::invalid_argument naming the joint and key: a joint unknown to the model, an unknown key, a value that is
// not a number, min_position > max_position, max_velocity <= 0 with has_velocity_limits.
std::vector<JointLimit> loadJointLimits(const sixdof_core::RobotModel& model, const YAML::Node& joint_limits,
                                        const std::vector<std::string>& joints);

}  // namespace sixdof_control
