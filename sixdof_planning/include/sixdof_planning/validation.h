#pragma once

#include <string>
#include <vector>

#include <geometry_msgs/Pose.h>
#include <sensor_msgs/JointState.h>

#include <sixdof_core/robot_model.h>
#include <moveit_msgs/CollisionObject.h>

#include "sixdof_planning/errors.h"

namespace sixdof_planning {

// Request checks. Each returns SUCCESS or the error code a MoveIt user expects, with a message naming the
// offending field (`what`) and value; `source` is the service or action answering. Checks of values any field
// may hold (numbers, poses, scaling factors, collision objects) fail with FAILURE; the caller recodes it for its
// field (recode(): INVALID_GOAL_CONSTRAINTS in a goal, INVALID_ROBOT_STATE in a robot state).

// A quaternion whose norm is further than this from 1 is rejected rather than normalised.
constexpr double kQuaternionNormTolerance = 1e-3;

ErrorCode validateFinite(double value, const std::string& what, const std::string& source);
// Finite position, finite quaternion of unit norm (+-kQuaternionNormTolerance).
ErrorCode validatePose(const geometry_msgs::Pose& pose, const std::string& what, const std::string& source);
// MoveIt's scaling factors: 0 means "not set" (1.0); otherwise (0, 1]. *effective gets the value to use.
ErrorCode validateScalingFactor(double value, const std::string& what, const std::string& source, double* effective);
// A request's velocity and acceleration scaling factors, each as validateScalingFactor; their fields are named
// <prefix>velocity_scaling_factor and <prefix>acceleration_scaling_factor.
struct ScalingFactors {
  double velocity = 1.0;
  double acceleration = 1.0;
};
ErrorCode validateScalingFactors(double velocity, double acceleration, const std::string& prefix,
                                 const std::string& source, ScalingFactors* effective);

ErrorCode validateGroup(const sixdof_core::RobotModel& model, const std::string& group, const std::string& source);
ErrorCode validateLink(const sixdof_core::RobotModel& model, const std::string& link, const std::string& source);
// Known, non-fixed joints, one position per name, no duplicates, finite values (INVALID_ROBOT_STATE).
ErrorCode validateJointState(const sixdof_core::RobotModel& model, const sensor_msgs::JointState& joint_state,
                             const std::string& source);
// A trajectory's joints: known, active (not fixed, not mimic), each named once (INVALID_MOTION_PLAN).
ErrorCode validateTrajectoryJoints(const sixdof_core::RobotModel& model, const std::vector<std::string>& joint_names,
                                   const std::string& source);
// A known operation; a non-empty id (except REMOVE: empty = all); for ADD/APPEND valid poses, at least one
// shape when shapes_required (attaching an existing world object needs none), primitive dimensions complete
// and positive, one pose per shape, meshes with finite vertices and in-range triangle indices; no planes and
// no subframes (not supported). `type` is kept as given.
ErrorCode validateCollisionObject(const moveit_msgs::CollisionObject& object, const std::string& what,
                                  const std::string& source, bool shapes_required = true);

// A number as a stream prints it ("0.001", "1e-08"), for error messages.
std::string formatNumber(double value);
// "a, b, c" for error messages.
std::string joinNames(const std::vector<std::string>& names);

}  // namespace sixdof_planning
