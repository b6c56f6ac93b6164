#include "sixdof_core/robot_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sixdof_core/result.h"

// The model's queries; parsing is in src/robot_model/ (urdf_parser.cpp, srdf_parser.cpp, package_resolver.cpp),
// RobotState in src/robot_model/robot_state.cpp.

namespace sixdof_core {

const char* toString(JointType type) {
  static constexpr const char* kNames[] = {"fixed", "revolute", "continuous", "prismatic"};
  return enumName<JointType::kPrismatic>(type, kNames, "");
}

bool JointModel::isMultiTurn() const {
  if (type == JointType::kContinuous) return true;
  return type == JointType::kRevolute && limits.upper - limits.lower > 2.0 * M_PI;
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RobotModelError("cannot read file '" + path + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// ---------------------------------------------------------------------------------------------------
// RobotModel

RobotModel::RobotModel(const std::string& urdf_xml, const std::string& srdf_xml, const PackageResolver& resolver) {
  parseUrdf(urdf_xml, resolver);
  if (!srdf_xml.empty()) parseSrdf(srdf_xml);
}

std::shared_ptr<const RobotModel> RobotModel::fromFiles(const std::string& urdf_path, const std::string& srdf_path,
                                                        const PackageResolver& resolver) {
  return std::make_shared<const RobotModel>(readTextFile(urdf_path), readTextFile(srdf_path), resolver);
}

int RobotModel::linkIndex(const std::string& name) const {
  auto it = link_index_.find(name);
  return it == link_index_.end() ? -1 : it->second;
}

int RobotModel::jointIndex(const std::string& name) const {
  auto it = joint_index_.find(name);
  return it == joint_index_.end() ? -1 : it->second;
}

const LinkModel& RobotModel::link(const std::string& name) const {
  const int index = linkIndex(name);
  if (index < 0) throw std::out_of_range("unknown link '" + name + "'");
  return links_[index];
}

const JointModel& RobotModel::joint(const std::string& name) const {
  const int index = jointIndex(name);
  if (index < 0) throw std::out_of_range("unknown joint '" + name + "'");
  return joints_[index];
}

Eigen::VectorXd RobotModel::defaultPositions() const {
  Eigen::VectorXd q(variableCount());
  for (size_t v = 0; v < variableCount(); ++v) {
    const auto& limits = variableJoint(v).limits;
    q[v] = (0.0 >= limits.lower && 0.0 <= limits.upper) ? 0.0 : 0.5 * (limits.lower + limits.upper);
  }
  return q;
}

std::vector<int> RobotModel::chainJoints(const std::string& base_link, const std::string& tip_link) const {
  const int base = linkIndex(base_link);
  int link = linkIndex(tip_link);
  if (base < 0) throw RobotModelError("unknown link '" + base_link + "'");
  if (link < 0) throw RobotModelError("unknown link '" + tip_link + "'");
  std::vector<int> joints;
  while (link != base) {
    if (link < 0 || links_[link].parent_joint < 0) {
      throw RobotModelError("link '" + tip_link + "' is not a descendant of '" + base_link + "'");
    }
    joints.push_back(links_[link].parent_joint);
    link = links_[link].parent_link;
  }
  std::reverse(joints.begin(), joints.end());
  return joints;
}

const JointGroup* RobotModel::findGroup(const std::string& name) const {
  for (const auto& group : groups_) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

const GroupState* RobotModel::findGroupState(const std::string& group, const std::string& name) const {
  for (const auto& state : group_states_) {
    if (state.group == group && state.name == name) return &state;
  }
  return nullptr;
}

std::vector<LinkGeometry> RobotModel::collisionGeometry() const {
  std::vector<LinkGeometry> geometry;
  for (const auto& link : links_) {
    if (!link.collision.shapes.empty()) geometry.push_back(link.collision);
  }
  return geometry;
}

}  // namespace sixdof_core
