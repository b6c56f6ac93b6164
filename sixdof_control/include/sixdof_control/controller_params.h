#pragma once
// The controllers a node serves, from the parameter server in ros_control's controllers.yaml layout:
//   <name>: {type: .../JointTrajectoryController, joints: [...], state_publish_rate,
//            constraints: {goal_time, stopped_velocity_tolerance, <joint>: {trajectory, goal}},
//            gripper_cmd: {goal_tolerance, stall_velocity_threshold, stall_timeout, allow_stalling}}
//   controller_list: [{name, action_ns: follow_joint_trajectory, type: FollowJointTrajectory, joints}, ...]
// `gains` are not read (the simulator's joints are ideal servos, a hardware plugin commands positions). The
// simulator's node and the driver node read them with these functions.

#include <ros/node_handle.h>

#include <optional>
#include <string>
#include <vector>

#include "sixdof_control/controller_joints.h"
#include "sixdof_core/control/gripper_controller.h"
#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_control {

struct TrajectoryControllerSetup {
  sixdof_core::TrajectoryControllerConfig config;  // every joint of controllers.yaml, mimic joints included
  ControllerJoints joints;
  double state_publish_rate = 50.0;  // Hz of <name>/state; 0 = no state topic
};

struct ControllerSetup {
  std::vector<TrajectoryControllerSetup> trajectory;
  // The controller that also serves <name>/gripper_cmd, on its first non-mimic joint.
  std::optional<sixdof_core::GripperControllerConfig> gripper;
};

// The controllers of the node: every FollowJointTrajectory controller of `controller_list` (nh), or the names in
// the private `~controllers`; gripper_cmd on the first of them with a `gripper_cmd` block, else on
// `gripper_controller` if it is one of them, else none, unless the private `~gripper_command_controller` names one
// ("" for none). Throws std::runtime_error naming the parameter when one is missing, mistyped or inconsistent, and
// std::invalid_argument when a controller's joint is not a moving joint of `robot` or mimics one it lacks.
ControllerSetup readControllerSetup(const ros::NodeHandle& nh, const ros::NodeHandle& pnh,
                                    const std::vector<RobotJoint>& robot);

// One line naming the controllers, e.g. "arm_controller, gripper_controller (+gripper_cmd)".
std::string controllerSummary(const ControllerSetup& setup);

}  // namespace sixdof_control
