#pragma once
// A gripper's grasp geometry from its links' shapes: the finger pads, which end of each finger joint opens it,
// the opening widths and the grasp frame (TCP). What the setup assistant writes into a package's grasping.yaml
// (docs/your_own_arm.md "Grippers"), and what the simulator's tests grasp with.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

// Contact points closer than this (m) to a pad's innermost point along the closing direction make up its
// contact surface.
constexpr double kPadSurfaceTolerance = 0.002;
// An approach direction (from where the fingers are jointed to the pads) within this angle (rad, 25 deg) of one of
// the parent link's axes is taken to be that axis: grippers sit square on their flange, their finger joints need
// not lie on its axis.
constexpr double kApproachSnap = 0.4363323129985824;

struct GripperQuery {
  std::string parent_link;          // the end effector's parent (the arm's tip): every result is in its frame
  std::vector<std::string> joints;  // the gripper's moving joints (its mimic joints may be listed too)
  // Given values (a setup assistant's answers) win over inferred ones; empty: inferred.
  std::vector<std::string> pad_links;                // two links with geometry
  std::optional<Eigen::Vector3d> closing_direction;  // in the parent frame
  std::map<std::string, double> open;                // actuated gripper joint -> position
  std::map<std::string, double> closed;
  std::optional<Eigen::Isometry3d> tcp;  // in the frame of tcp_parent
  std::string tcp_parent;                // a link rigidly attached to parent_link (empty: parent_link)
  // A link of this name is the TCP: it wins over inference (and a given tcp is then refused).
  std::string tcp_link = "tcp";
};

// An actuated finger joint: the pads' distance at both ends of its range (the other actuated joints halfway).
struct FingerJoint {
  std::string joint;
  double width_at_lower = 0.0;
  double width_at_upper = 0.0;
  double open = 0.0;
  double closed = 0.0;
};

struct GraspGeometry {
  std::string parent_link;
  // The grasp frame in the parent frame: midway between the pads' contact surfaces, at their centre depth (the
  // gripper half closed); z along the approach (from where the fingers are jointed towards the pads, snapped to
  // a parent axis within kApproachSnap), y along the closing direction, signed so that the frame is the least
  // rotation from the parent's.
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity();
  std::string tcp_source;  // "link '<tcp_link>'", "given", "pads" or "parent link" (nothing better found)
  std::vector<std::string> pad_links;     // the two pads (none found: empty)
  std::vector<std::string> finger_links;  // every link the finger joints move that has geometry, model order
  Eigen::Vector3d closing_direction = Eigen::Vector3d::UnitY();  // unit, parent frame (the inferred TCP's y)
  Eigen::Vector3d approach_direction = Eigen::Vector3d::UnitZ();  // unit, parent frame: the TCP's z
  std::vector<FingerJoint> finger_joints;  // the actuated gripper joints, model order
  std::map<std::string, double> open;      // actuated gripper joint -> position (no mimic joints)
  std::map<std::string, double> closed;
  double open_width = 0.0;    // m between the pads' contact surfaces when open (0 without pads)
  double closed_width = 0.0;  // ... when closed (negative: the pads' geometry overlaps)
  // How far the finger links reach beyond the TCP along the approach, anywhere between open and closed: how high
  // above a table a top-down grasp must hold its TCP.
  double reach = 0.0;
  // How far an object between the pads may extend from the TCP back towards the palm: the distance along the
  // approach to the nearest shape of the parent link or a link fixed below it whose bounding box (in the TCP frame)
  // lies across the gap between the pads (infinity when none does).
  double palm_depth = 0.0;
  std::vector<std::string> warnings;  // what could not be inferred and what was taken instead
};

// The grasp geometry of the gripper `query.joints` below `query.parent_link`. Pads: the links the finger joints
// move, split into two sides along the closing direction (the main direction of their motion relative to each
// other), and on each side the one reaching furthest in. Geometry: collision shapes, visual ones for a link
// without. A finger joint opens the gripper at the end of its range where the pads are further apart; mimic
// joints follow their master (never their own limits). What cannot be inferred is a warning with a fallback
// (open = upper limits, TCP = the parent link), never an error. Throws std::invalid_argument naming a bad query:
// an unknown link or joint, a fixed joint, no actuated joint, given pads that are not two links with geometry, a
// zero closing direction, a given position of a joint that is not actuated in the gripper or outside its limits,
// a given tcp while the model has a link named query.tcp_link, a tcp_parent that is unknown or moved by the
// finger joints.
GraspGeometry analyzeGripper(const RobotModelConstPtr& model, const GripperQuery& query);

}  // namespace sixdof_core
