#pragma once
// moveit_msgs/Constraints as move_group evaluates them (MoveIt's kinematic_constraints): path constraints for the
// planner and Cartesian paths, and every constraint of a check_state_validity request.

#include <string>
#include <vector>

#include <moveit_msgs/ConstraintEvalResult.h>
#include <moveit_msgs/Constraints.h>
#include <sixdof_core/planning_context.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_planning/errors.h"

namespace sixdof_planning {

// True when the message holds no constraint of any kind.
bool constraintsEmpty(const moveit_msgs::Constraints& constraints);

// The core's path constraints of `constraints` for planning group `group`: a joint constraint keeps its joint in
// [position - tolerance_below, position + tolerance_above] (a joint of the group narrows the planner's sampling;
// any joint is checked at every state); a position constraint keeps the link's point (target_point_offset in the
// link frame) inside the constraint region (any of its boxes, spheres and cylinders, posed in header.frame_id: the
// planning frame or a robot link). Orientation and visibility constraints, and regions with meshes, are refused
// with FAILURE naming the field (`what`, e.g. "path_constraints").
ErrorCode toPathConstraints(const sixdof_core::RobotModel& model, const std::string& group,
                            const moveit_msgs::Constraints& constraints, const std::string& what,
                            const std::string& source, sixdof_core::PathConstraints* out);

// Every joint, position and orientation constraint of `constraints` evaluated at `state`, in that order (as MoveIt's
// KinematicConstraintSet): satisfied and a distance (joint: |error|; position: to the nearest region primitive's
// centre; orientation: the largest axis error). Visibility constraints are refused with FAILURE; so are malformed
// constraints (unknown joint or link, negative tolerances, non-finite values, a non-unit quaternion).
ErrorCode evaluateConstraints(const sixdof_core::RobotState& state, const moveit_msgs::Constraints& constraints,
                              const std::string& what, const std::string& source,
                              std::vector<moveit_msgs::ConstraintEvalResult>* results);

}  // namespace sixdof_planning
