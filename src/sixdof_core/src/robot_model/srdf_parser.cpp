// RobotModel::parseSrdf: groups, group states, end effectors, virtual joints, disabled collisions.
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <set>
#include <sstream>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

namespace {

std::string requiredAttribute(const tinyxml2::XMLElement* e, const char* attribute, const std::string& context) {
  const char* value = e->Attribute(attribute);
  if (!value || std::string(value).empty()) {
    throw RobotModelError("SRDF: <" + std::string(e->Name()) + "> " + context + "has no '" + attribute +
                          "' attribute (line " + std::to_string(e->GetLineNum()) + ")");
  }
  return value;
}

}  // namespace

void RobotModel::parseSrdf(const std::string& srdf_xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(srdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw RobotModelError(std::string("SRDF: XML error: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") throw RobotModelError("SRDF: root element is not <robot>");
  const std::string srdf_name = requiredAttribute(robot, "name", "");
  if (srdf_name != name_) {
    throw RobotModelError("SRDF: robot name '" + srdf_name + "' does not match the URDF's '" + name_ + "'");
  }
  auto check_link = [&](const std::string& link, const std::string& context) {
    if (linkIndex(link) < 0) throw RobotModelError("SRDF: " + context + " refers to unknown link '" + link + "'");
  };
  auto check_joint = [&](const std::string& joint, const std::string& context) {
    if (jointIndex(joint) < 0) throw RobotModelError("SRDF: " + context + " refers to unknown joint '" + joint + "'");
  };

  // Groups are collected first, then expanded, because subgroups may be declared after their users.
  struct RawGroup {
    std::set<int> joints;
    std::set<int> links;
  };
  std::map<std::string, RawGroup> raw;
  std::vector<std::pair<const tinyxml2::XMLElement*, std::string>> state_elements;
  for (const auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string element = e->Name();
    if (element == "group") {
      JointGroup group;
      group.name = requiredAttribute(e, "name", "");
      if (findGroup(group.name)) throw RobotModelError("SRDF: group '" + group.name + "' is declared twice");
      const std::string context = "group '" + group.name + "'";
      RawGroup& contents = raw[group.name];
      for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
        const std::string child = c->Name();
        if (child == "joint") {
          const std::string joint = requiredAttribute(c, "name", "in " + context + " ");
          check_joint(joint, context);
          contents.joints.insert(jointIndex(joint));
          contents.links.insert(linkIndex(joints_[jointIndex(joint)].child_link));
        } else if (child == "link") {
          const std::string link = requiredAttribute(c, "name", "in " + context + " ");
          check_link(link, context);
          contents.links.insert(linkIndex(link));
          if (links_[linkIndex(link)].parent_joint >= 0) contents.joints.insert(links_[linkIndex(link)].parent_joint);
        } else if (child == "chain") {
          if (group.isChain()) throw RobotModelError("SRDF: " + context + " has more than one <chain>");
          group.chain_base = requiredAttribute(c, "base_link", "in " + context + " ");
          group.chain_tip = requiredAttribute(c, "tip_link", "in " + context + " ");
          check_link(group.chain_base, context + " chain");
          check_link(group.chain_tip, context + " chain");
          std::vector<int> chain;
          try {
            chain = chainJoints(group.chain_base, group.chain_tip);
          } catch (const RobotModelError& error) {
            throw RobotModelError("SRDF: " + context + ": " + error.what());
          }
          for (int j : chain) {
            contents.joints.insert(j);
            contents.links.insert(linkIndex(joints_[j].child_link));
          }
        } else if (child == "group") {
          group.subgroups.push_back(requiredAttribute(c, "name", "in " + context + " "));
        } else {
          throw RobotModelError("SRDF: " + context + " has an unknown element <" + child + ">");
        }
      }
      groups_.push_back(group);
    } else if (element == "group_state") {
      state_elements.emplace_back(e, requiredAttribute(e, "name", ""));
    } else if (element == "end_effector") {
      EndEffector eef;
      eef.name = requiredAttribute(e, "name", "");
      eef.parent_link = requiredAttribute(e, "parent_link", "'" + eef.name + "' ");
      eef.group = requiredAttribute(e, "group", "'" + eef.name + "' ");
      if (const char* parent_group = e->Attribute("parent_group")) eef.parent_group = parent_group;
      check_link(eef.parent_link, "end effector '" + eef.name + "'");
      end_effectors_.push_back(eef);
    } else if (element == "virtual_joint") {
      VirtualJoint vj;
      vj.name = requiredAttribute(e, "name", "");
      vj.type = requiredAttribute(e, "type", "'" + vj.name + "' ");
      vj.parent_frame = requiredAttribute(e, "parent_frame", "'" + vj.name + "' ");
      vj.child_link = requiredAttribute(e, "child_link", "'" + vj.name + "' ");
      if (vj.type != "fixed" && vj.type != "floating" && vj.type != "planar") {
        throw RobotModelError("SRDF: virtual joint '" + vj.name + "' has unknown type '" + vj.type + "'");
      }
      check_link(vj.child_link, "virtual joint '" + vj.name + "'");
      if (vj.child_link != rootLink()) {
        throw RobotModelError("SRDF: virtual joint '" + vj.name + "' attaches '" + vj.child_link +
                              "', which is not the URDF root link '" + rootLink() + "'");
      }
      virtual_joints_.push_back(vj);
    } else if (element == "passive_joint") {
      const std::string joint = requiredAttribute(e, "name", "");
      check_joint(joint, "passive joint");
      passive_joints_.push_back(joint);
    } else if (element == "disable_collisions") {
      DisabledCollisionPair pair;
      pair.link1 = requiredAttribute(e, "link1", "");
      pair.link2 = requiredAttribute(e, "link2", "");
      if (const char* reason = e->Attribute("reason")) pair.reason = reason;
      check_link(pair.link1, "disable_collisions");
      check_link(pair.link2, "disable_collisions");
      disabled_collisions_.push_back(pair);
    } else {
      throw RobotModelError("SRDF: unknown element <" + element + "> (line " + std::to_string(e->GetLineNum()) + ")");
    }
  }

  // Expand subgroups (depth first, rejecting cycles and unknown names).
  std::map<std::string, int> visit_state;  // 1 = in progress, 2 = done
  std::function<void(const std::string&)> expand = [&](const std::string& name) {
    if (visit_state[name] == 2) return;
    if (visit_state[name] == 1) throw RobotModelError("SRDF: group '" + name + "' contains itself via subgroups");
    visit_state[name] = 1;
    const JointGroup* group = findGroup(name);
    for (const auto& sub : group->subgroups) {
      if (!findGroup(sub)) {
        throw RobotModelError("SRDF: group '" + name + "' refers to unknown subgroup '" + sub + "'");
      }
      expand(sub);
      raw[name].joints.insert(raw[sub].joints.begin(), raw[sub].joints.end());
      raw[name].links.insert(raw[sub].links.begin(), raw[sub].links.end());
    }
    visit_state[name] = 2;
  };
  for (auto& group : groups_) {
    expand(group.name);
    // Joint and link indices follow topological order, so the sets are already in model order.
    for (int j : raw[group.name].joints) {
      group.joints.push_back(joints_[j].name);
      if (joints_[j].isActive()) group.active_joints.push_back(joints_[j].name);
    }
    for (int l : raw[group.name].links) group.links.push_back(links_[l].name);
    if (group.joints.empty() && group.links.empty()) {
      throw RobotModelError("SRDF: group '" + group.name + "' is empty");
    }
  }

  for (const auto& eef : end_effectors_) {
    if (!findGroup(eef.group)) {
      throw RobotModelError("SRDF: end effector '" + eef.name + "' refers to unknown group '" + eef.group + "'");
    }
    if (!eef.parent_group.empty() && !findGroup(eef.parent_group)) {
      throw RobotModelError("SRDF: end effector '" + eef.name + "' refers to unknown parent group '" +
                            eef.parent_group + "'");
    }
  }

  for (const auto& [e, name] : state_elements) {
    GroupState state;
    state.name = name;
    state.group = requiredAttribute(e, "group", "'" + name + "' ");
    const std::string context = "group_state '" + name + "' of group '" + state.group + "'";
    const JointGroup* group = findGroup(state.group);
    if (!group) throw RobotModelError("SRDF: group_state '" + name + "' refers to unknown group '" + state.group + "'");
    if (findGroupState(state.group, name)) throw RobotModelError("SRDF: " + context + " is declared twice");
    for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      if (std::string(c->Name()) != "joint") {
        throw RobotModelError("SRDF: " + context + " has an unknown element <" + c->Name() + ">");
      }
      const std::string joint_name = requiredAttribute(c, "name", "in " + context + " ");
      check_joint(joint_name, context);
      if (std::find(group->joints.begin(), group->joints.end(), joint_name) == group->joints.end()) {
        throw RobotModelError("SRDF: " + context + " sets joint '" + joint_name + "', which is not in the group");
      }
      const std::string text = requiredAttribute(c, "value", "'" + joint_name + "' in " + context + " ");
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
        throw RobotModelError("SRDF: " + context + ": value '" + text + "' of joint '" + joint_name +
                              "' is not a number");
      }
      const JointModel& joint = joints_[jointIndex(joint_name)];
      // A mimic joint follows its master and is not held to its own limits (MoveIt's rule).
      if (joint.limits.bounded && joint.type != JointType::kFixed && !joint.mimic &&
          (value < joint.limits.lower || value > joint.limits.upper)) {
        throw RobotModelError("SRDF: " + context + ": value " + text + " of joint '" + joint_name +
                              "' is outside its limits [" + std::to_string(joint.limits.lower) + ", " +
                              std::to_string(joint.limits.upper) + "]");
      }
      state.values[joint_name] = value;
    }
    group_states_.push_back(state);
  }
}

}  // namespace sixdof_core
