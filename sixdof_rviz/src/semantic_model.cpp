#include "sixdof_rviz/semantic_model.h"

#include <cstdlib>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

namespace sixdof_rviz {

std::shared_ptr<const sixdof_core::RobotModel> loadRobotModel(const std::string& urdf_xml,
                                                               const std::string& srdf_xml) {
  if (urdf_xml.empty()) throw std::invalid_argument("URDF: empty robot description");
  const char* package_path = std::getenv("ROS_PACKAGE_PATH");
  try {
    return std::make_shared<const sixdof_core::RobotModel>(
        urdf_xml, srdf_xml, sixdof_core::PackageResolver::fromRosPackagePath(package_path ? package_path : ""));
  } catch (const sixdof_core::RobotModelError& e) {
    throw std::invalid_argument(e.what());
  }
}

SemanticModel::SemanticModel(const std::string& urdf_xml, const std::string& srdf_xml) {
  if (srdf_xml.empty()) throw std::invalid_argument("SRDF: empty semantic description");
  model_ = loadRobotModel(urdf_xml, srdf_xml);
  urdf_ = urdf::parseURDF(urdf_xml);
  if (!urdf_) throw std::invalid_argument("URDF: the robot description could not be parsed");

  for (size_t v = 0; v < model_->variableCount(); ++v) {
    const sixdof_core::JointModel& joint = model_->variableJoint(v);
    active_joints_[joint.name] = ActiveJoint{joint.name, joint.limits.bounded, joint.limits.lower, joint.limits.upper};
  }
  for (const sixdof_core::JointGroup& g : model_->groups()) {
    groups_.push_back(PlanningGroup{g.name, g.active_joints, g.chain_base, g.chain_tip});
  }
  for (const sixdof_core::GroupState& s : model_->groupStates()) {
    NamedState state{s.group, s.name, {}};
    // Mimic joints may be listed; only the active ones define the goal.
    for (const auto& [joint, value] : s.values) {
      if (active_joints_.count(joint)) state.values[joint] = value;
    }
    // A named state is a complete goal for the panel and the goal marker.
    for (const auto& joint : group(s.group)->joints) {
      if (!state.values.count(joint)) {
        throw std::invalid_argument("SRDF: group_state '" + s.name + "' misses joint '" + joint + "' of group '" +
                                    s.group + "'");
      }
    }
    named_states_.push_back(state);
  }
}

const PlanningGroup* SemanticModel::group(const std::string& name) const {
  for (const auto& group : groups_) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

const ActiveJoint* SemanticModel::activeJoint(const std::string& name) const {
  auto it = active_joints_.find(name);
  return it == active_joints_.end() ? nullptr : &it->second;
}

std::vector<std::string> SemanticModel::namedStates(const std::string& group) const {
  std::vector<std::string> names;
  for (const auto& state : named_states_) {
    if (state.group == group) names.push_back(state.name);
  }
  return names;
}

const NamedState* SemanticModel::namedState(const std::string& group, const std::string& name) const {
  for (const auto& state : named_states_) {
    if (state.group == group && state.name == name) return &state;
  }
  return nullptr;
}

}  // namespace sixdof_rviz
