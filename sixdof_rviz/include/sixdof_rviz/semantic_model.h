#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include "sixdof_core/robot_model.h"

namespace sixdof_rviz {

using JointValues = std::map<std::string, double>;

// A joint the user can move (not fixed, not a mimic). Limits follow the core's convention (docs/design.md
// "Joint limits"): a continuous joint is unbounded, with the nominal range -pi..pi.
struct ActiveJoint {
  std::string name;
  bool bounded = true;  // false for continuous joints
  double lower = 0.0;
  double upper = 0.0;
};

// An SRDF planning group resolved against the URDF.
struct PlanningGroup {
  std::string name;
  std::vector<std::string> joints;  // active joints, in the core model's order (root to tip for a chain)
  std::string base_link;            // set for chain groups only
  std::string tip_link;             // set for chain groups only
};

struct NamedState {
  std::string group;
  std::string name;
  JointValues values;
};

// The core robot model (sixdof_core_model: the project's only URDF/SRDF reader) for a ROS package path: mesh
// URIs resolve against ROS_PACKAGE_PATH. srdf_xml may be empty (kinematics only). Throws
// std::invalid_argument naming the problem.
std::shared_ptr<const sixdof_core::RobotModel> loadRobotModel(const std::string& urdf_xml,
                                                               const std::string& srdf_xml = "");

// The part of URDF + SRDF the rviz plugins need: groups, their joints and tip links, named states, read by the
// core robot model. ROS-free so that it is testable without a master. Throws std::invalid_argument on malformed
// input, naming the offending element.
class SemanticModel {
 public:
  SemanticModel(const std::string& urdf_xml, const std::string& srdf_xml);

  const std::shared_ptr<const sixdof_core::RobotModel>& robotModel() const { return model_; }
  // urdfdom's model of the same description, for rviz::Robot's visual meshes only (the core model carries
  // collision geometry, not visuals and materials).
  const urdf::ModelInterfaceSharedPtr& urdf() const { return urdf_; }
  const std::vector<PlanningGroup>& groups() const { return groups_; }
  const PlanningGroup* group(const std::string& name) const;
  const ActiveJoint* activeJoint(const std::string& name) const;
  std::vector<std::string> namedStates(const std::string& group) const;
  const NamedState* namedState(const std::string& group, const std::string& name) const;

 private:
  std::shared_ptr<const sixdof_core::RobotModel> model_;
  urdf::ModelInterfaceSharedPtr urdf_;
  std::map<std::string, ActiveJoint> active_joints_;
  std::vector<PlanningGroup> groups_;
  std::vector<NamedState> named_states_;
};

}  // namespace sixdof_rviz
