#pragma once
// Controller configuration from the parameter server, in ros_control's controllers.yaml layout:
//   <name>: {type: .../JointTrajectoryController, joints: [...], state_publish_rate,
//            constraints: {goal_time, stopped_velocity_tolerance, <joint>: {trajectory, goal}},
//            gripper_cmd: {goal_tolerance, stall_velocity_threshold, stall_timeout, allow_stalling}}
// `gains` are not read: the World's joint servos are configured by the World itself.

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "sixdof_sim/controllers.h"
#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Throws std::runtime_error naming the parameter when it is missing, mistyped or inconsistent.
TrajectoryControllerConfig readTrajectoryControllerConfig(const ros::NodeHandle& nh, const std::string& name,
                                                          const std::vector<JointInfo>& robot_joints);

// <name>/state_publish_rate (Hz, default 50 as joint_trajectory_controller; 0 = no state topic). Throws
// std::runtime_error unless it is a finite number >= 0.
double readStatePublishRate(const ros::NodeHandle& nh, const std::string& name);

// The controllers the simulator runs: the names in `controller_list` (moveit_simple_controller_manager's format,
// from the same controllers config as the controllers themselves). Every entry must be a FollowJointTrajectory
// controller on `follow_joint_trajectory`, the action the simulator serves. Throws std::runtime_error naming the
// parameter when the list is missing or malformed.
std::vector<std::string> readControllerList(const ros::NodeHandle& nh);

// The controller that also serves gripper_cmd: the first of `controllers` with a `gripper_cmd` block, else
// `gripper_controller` (the name docs/design.md gives that action) if it is one of them, else "" (no gripper).
std::string defaultGripperCommandController(const ros::NodeHandle& nh, const std::vector<std::string>& controllers);

// The gripper_cmd action of controller `name` drives its first non-mimic joint.
GripperControllerConfig readGripperControllerConfig(const ros::NodeHandle& nh, const std::string& name,
                                                    const std::vector<JointInfo>& robot_joints);

}  // namespace sixdof_sim
