#pragma once
// A config package's config/grasping.yaml (the setup assistant writes it; docs/your_own_arm.md "Grippers"), which
// move_group reads once from its robot_description_grasping parameter and serves in get_robot_model, so that
// scripts take the gripper's TCP, open and closed states and widths from the package instead of link names.

#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <sixdof_core/robot_model.h>

namespace sixdof_planning {

// One of the gripper's states: an SRDF group state of the gripper group and its actuated joints' positions.
struct GripperState {
  std::string name;
  std::map<std::string, double> positions;
};

struct GraspingConfig {
  std::string group;         // the gripper's planning group
  std::string end_effector;  // its SRDF end effector
  std::string tcp_frame;     // the TCP's name (a URDF link at `tcp` when the model has it)
  std::string parent_link;   // the end effector's parent link: the frame of tcp and the directions
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
  GripperState open;
  GripperState closed;
  double max_opening = 0.0;   // m between the pads when open (> 0)
  double closed_width = 0.0;  // m between them when closed
  double finger_reach = 0.0;  // m beyond the TCP along the approach (negative: the fingertips stop short of it)
  double palm_depth = 0.0;    // m behind the TCP to the palm (> 0; infinity: no palm across the pads)
  std::vector<std::string> pad_links;
  Eigen::Vector3d closing_direction = Eigen::Vector3d::UnitY();   // unit
  Eigen::Vector3d approach_direction = Eigen::Vector3d::UnitZ();  // unit
  // A suction tool (the `suction` mapping): its cup frame, vacuum controller and payload; no fingers.
  std::string suction_cup;  // empty: a gripper with fingers
  std::string vacuum_controller;
  double max_payload = 0.0;
};

// Reads grasping.yaml text against the model it is for. `source` names the text in messages (the parameter).
// Required: group, tcp {parent_link, xyz, rpy}, open and closed {state, positions}, max_opening, closing_direction,
// approach_direction; optional: end_effector (default: the SRDF end effector of the group), tcp.frame, tcp.source,
// closed_width, finger_reach, palm_depth (default infinity), pad_links, and grasp_fix (the simulator's; not read
// here). A suction tool has a `suction` mapping (cup_link required; controller, max_payload and the simulator's
// tilt_tolerance, contact_distance, arm_name optional) instead of open, closed, max_opening and closing_direction.
// Throws ConfigError (config.h) naming `source` and the key on anything that does not fit the model: an
// unknown key, group, end effector, link or joint, a state position outside its joint's limits, a state of a mimic
// or non-gripper joint, a state that disagrees with the SRDF's group state of the same name, a tcp.frame link
// that is not rigidly fixed to parent_link at tcp, a width or reach that is not a finite number in range, a zero
// direction.
GraspingConfig parseGraspingConfig(const std::string& yaml_text, const sixdof_core::RobotModel& model,
                                   const std::string& source);

}  // namespace sixdof_planning
