#include "sixdof_rviz/semantic_model.h"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

namespace sixdof_rviz {
namespace {

std::string requiredAttribute(const tinyxml2::XMLElement& element, const char* attribute) {
  const char* value = element.Attribute(attribute);
  if (value == nullptr || *value == '\0') {
    throw std::invalid_argument(std::string("SRDF: <") + element.Name() + "> without attribute '" + attribute + "'");
  }
  return value;
}

void appendUnique(const std::vector<std::string>& items, std::vector<std::string>* out) {
  for (const auto& item : items) {
    if (std::find(out->begin(), out->end(), item) == out->end()) out->push_back(item);
  }
}

}  // namespace

SemanticModel::SemanticModel(const std::string& urdf_xml, const std::string& srdf_xml) {
  if (urdf_xml.empty()) throw std::invalid_argument("URDF: empty robot description");
  urdf_ = urdf::parseURDF(urdf_xml);
  if (!urdf_) throw std::invalid_argument("URDF: the robot description could not be parsed");
  for (const auto& [name, joint] : urdf_->joints_) {
    if (joint->type == urdf::Joint::FIXED || joint->type == urdf::Joint::FLOATING ||
        joint->type == urdf::Joint::PLANAR || joint->mimic) {
      continue;
    }
    ActiveJoint active;
    active.name = name;
    active.bounded = joint->type != urdf::Joint::CONTINUOUS;
    if (active.bounded) {
      if (!joint->limits) throw std::invalid_argument("URDF: joint '" + name + "' has no <limit>");
      active.lower = joint->limits->lower;
      active.upper = joint->limits->upper;
    }
    active_joints_[name] = active;
  }
  parseSrdf(srdf_xml);
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

bool SemanticModel::isActive(const std::string& joint) const { return active_joints_.count(joint) > 0; }

std::vector<std::string> SemanticModel::chainJoints(const std::string& base, const std::string& tip) const {
  if (!urdf_->getLink(base)) throw std::invalid_argument("SRDF: chain base link '" + base + "' is not in the URDF");
  if (!urdf_->getLink(tip)) throw std::invalid_argument("SRDF: chain tip link '" + tip + "' is not in the URDF");
  std::vector<std::string> joints;
  urdf::LinkConstSharedPtr link = urdf_->getLink(tip);
  while (link->name != base) {
    if (!link->parent_joint) {
      throw std::invalid_argument("SRDF: link '" + base + "' is not an ancestor of chain tip '" + tip + "'");
    }
    if (isActive(link->parent_joint->name)) joints.push_back(link->parent_joint->name);
    link = urdf_->getLink(link->parent_joint->parent_link_name);
  }
  std::reverse(joints.begin(), joints.end());
  return joints;
}

void SemanticModel::parseSrdf(const std::string& srdf_xml) {
  tinyxml2::XMLDocument doc;
  if (srdf_xml.empty()) throw std::invalid_argument("SRDF: empty semantic description");
  if (doc.Parse(srdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::invalid_argument(std::string("SRDF: XML error: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw std::invalid_argument("SRDF: no <robot> element");

  // Subgroups may refer to groups defined later: collect the raw definitions first.
  std::map<std::string, const tinyxml2::XMLElement*> definitions;
  std::vector<std::string> order;
  for (auto* e = robot->FirstChildElement("group"); e != nullptr; e = e->NextSiblingElement("group")) {
    std::string name = requiredAttribute(*e, "name");
    if (!definitions.emplace(name, e).second) throw std::invalid_argument("SRDF: group '" + name + "' defined twice");
    order.push_back(name);
  }
  std::map<std::string, PlanningGroup> resolved;
  std::vector<std::string> resolving;
  std::function<const PlanningGroup&(const std::string&)> resolve = [&](const std::string& name) -> const PlanningGroup& {
    auto done = resolved.find(name);
    if (done != resolved.end()) return done->second;
    auto def = definitions.find(name);
    if (def == definitions.end()) throw std::invalid_argument("SRDF: unknown subgroup '" + name + "'");
    if (std::find(resolving.begin(), resolving.end(), name) != resolving.end()) {
      throw std::invalid_argument("SRDF: group '" + name + "' contains itself");
    }
    resolving.push_back(name);
    PlanningGroup group;
    group.name = name;
    for (auto* c = def->second->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
      const std::string kind = c->Name();
      if (kind == "chain") {
        group.base_link = requiredAttribute(*c, "base_link");
        group.tip_link = requiredAttribute(*c, "tip_link");
        appendUnique(chainJoints(group.base_link, group.tip_link), &group.joints);
      } else if (kind == "joint") {
        std::string joint = requiredAttribute(*c, "name");
        if (!urdf_->getJoint(joint)) {
          throw std::invalid_argument("SRDF: group '" + name + "' names joint '" + joint + "' not in the URDF");
        }
        if (isActive(joint)) appendUnique({joint}, &group.joints);
      } else if (kind == "link") {
        std::string link_name = requiredAttribute(*c, "name");
        auto link = urdf_->getLink(link_name);
        if (!link) throw std::invalid_argument("SRDF: group '" + name + "' names link '" + link_name + "' not in the URDF");
        if (link->parent_joint && isActive(link->parent_joint->name)) {
          appendUnique({link->parent_joint->name}, &group.joints);
        }
      } else if (kind == "group") {
        appendUnique(resolve(requiredAttribute(*c, "name")).joints, &group.joints);
      } else {
        throw std::invalid_argument("SRDF: group '" + name + "' has unknown element <" + kind + ">");
      }
    }
    resolving.pop_back();
    return resolved.emplace(name, group).first->second;
  };
  for (const auto& name : order) groups_.push_back(resolve(name));

  for (auto* e = robot->FirstChildElement("group_state"); e != nullptr; e = e->NextSiblingElement("group_state")) {
    NamedState state;
    state.name = requiredAttribute(*e, "name");
    state.group = requiredAttribute(*e, "group");
    const PlanningGroup* owner = group(state.group);
    if (owner == nullptr) {
      throw std::invalid_argument("SRDF: group_state '" + state.name + "' refers to unknown group '" + state.group + "'");
    }
    for (auto* j = e->FirstChildElement("joint"); j != nullptr; j = j->NextSiblingElement("joint")) {
      std::string joint = requiredAttribute(*j, "name");
      double value = 0.0;
      if (j->QueryDoubleAttribute("value", &value) != tinyxml2::XML_SUCCESS) {
        throw std::invalid_argument("SRDF: group_state '" + state.name + "' joint '" + joint + "' has no numeric value");
      }
      // Mimic joints may be listed; only the active ones define the goal.
      if (isActive(joint)) state.values[joint] = value;
    }
    for (const auto& joint : owner->joints) {
      if (!state.values.count(joint)) {
        throw std::invalid_argument("SRDF: group_state '" + state.name + "' misses joint '" + joint + "' of group '" +
                                    state.group + "'");
      }
    }
    named_states_.push_back(state);
  }
}

}  // namespace sixdof_rviz
