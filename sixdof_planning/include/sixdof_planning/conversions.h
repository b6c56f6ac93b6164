#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <sensor_msgs/JointState.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <sixdof_core/geometry.h>
#include <sixdof_core/robot_model.h>
#include <sixdof_core/trajectory.h>

namespace sixdof_planning {

// The quaternion is normalised: callers validate it first (validation.h), so this only removes rounding.
Eigen::Isometry3d poseToEigen(const geometry_msgs::Pose& pose);
geometry_msgs::Pose eigenToPose(const Eigen::Isometry3d& pose);

// The core's shape type of a shape_msgs/SolidPrimitive type: BOX, SPHERE or CYLINDER (their dimensions in
// sixdof_core/primitive_dimensions.h); none for any other.
std::optional<sixdof_core::ShapeType> primitiveType(uint8_t msg_type);

// Every moving joint of the state (active and mimic joints, as a joint_states publisher sends them).
sensor_msgs::JointState toJointState(const sixdof_core::RobotState& state);

trajectory_msgs::JointTrajectory toJointTrajectory(const sixdof_core::Trajectory& trajectory);
sixdof_core::Trajectory fromJointTrajectory(const trajectory_msgs::JointTrajectory& trajectory);

}  // namespace sixdof_planning
