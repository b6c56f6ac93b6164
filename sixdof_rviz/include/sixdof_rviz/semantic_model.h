#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <urdf_model/model.h>
#include <urdf_world/types.h>

namespace sixdof_rviz {

using JointValues = std::map<std::string, double>;

// A joint the user can move (not fixed, not a mimic).
struct ActiveJoint {
  std::string name;
  bool bounded = true;  // false for continuous joints
  double lower = 0.0;
  double upper = 0.0;
};

// An SRDF planning group resolved against the URDF.
struct PlanningGroup {
  std::string name;
  std::vector<std::string> joints;  // active joints, root to tip
  std::string base_link;            // set for chain groups only
  std::string tip_link;             // set for chain groups only
};

struct NamedState {
  std::string group;
  std::string name;
  JointValues values;
};

// The part of URDF + SRDF the rviz plugins need: groups, their joints and tip links, named states.
// ROS-free so that it is testable without a master. Throws std::invalid_argument on malformed input,
// naming the offending element.
class SemanticModel {
 public:
  SemanticModel(const std::string& urdf_xml, const std::string& srdf_xml);

  const urdf::ModelInterfaceSharedPtr& urdf() const { return urdf_; }
  const std::vector<PlanningGroup>& groups() const { return groups_; }
  const PlanningGroup* group(const std::string& name) const;
  const ActiveJoint* activeJoint(const std::string& name) const;
  std::vector<std::string> namedStates(const std::string& group) const;
  const NamedState* namedState(const std::string& group, const std::string& name) const;

 private:
  void parseSrdf(const std::string& srdf_xml);
  std::vector<std::string> chainJoints(const std::string& base, const std::string& tip) const;
  bool isActive(const std::string& joint) const;

  urdf::ModelInterfaceSharedPtr urdf_;
  std::map<std::string, ActiveJoint> active_joints_;
  std::vector<PlanningGroup> groups_;
  std::vector<NamedState> named_states_;
};

}  // namespace sixdof_rviz
