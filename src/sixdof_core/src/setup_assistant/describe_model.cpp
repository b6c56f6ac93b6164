// describeModel(): what the setup assistant's front end needs to know of a model, as YAML.
#include <map>
#include <sstream>

#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/kinematics.h"
#include "sixdof_core/setup_assistant.h"
#include "yaml_text.h"

namespace sixdof_core {

namespace {

// rpy of a rotation, without negative zeros.
Eigen::Vector3d rpyOf(const Eigen::Matrix3d& rotation) { return rpyFromRotation(rotation) + Eigen::Vector3d::Zero(); }

// A link's shape as a YAML flow mapping: type, its sizes, and its origin in the link frame.
std::string shapeYaml(const PlacedShape& placed) {
  const Shape& shape = placed.shape;
  std::ostringstream out;
  switch (shape.type) {
    case ShapeType::kBox:
      out << "{type: box, size: " << yamlVector(shape.box_size);
      break;
    case ShapeType::kSphere:
      out << "{type: sphere, radius: " << yamlNumber(shape.radius);
      break;
    case ShapeType::kCylinder:
      out << "{type: cylinder, radius: " << yamlNumber(shape.radius) << ", length: " << yamlNumber(shape.length);
      break;
    case ShapeType::kMesh:
      out << "{type: mesh";
      break;
  }
  out << ", xyz: " << yamlVector(placed.origin.translation())
      << ", rpy: " << yamlVector(rpyOf(placed.origin.linear())) << "}";
  return out.str();
}

// The link's collision shapes, else its visual ones.
std::string shapesYaml(const LinkModel& link) {
  std::vector<std::string> shapes;
  for (const auto& placed : link.collision.shapes) shapes.push_back(shapeYaml(placed));
  if (shapes.empty()) {
    for (const auto& visual : link.visuals) shapes.push_back(shapeYaml(visual.placed));
  }
  std::string out = "[";
  for (size_t i = 0; i < shapes.size(); ++i) out += (i ? ", " : "") + shapes[i];
  return out + "]";
}

}  // namespace

std::string describeModel(const RobotModel& model, const DisabledCollisions* collisions) {
  std::ostringstream out;
  out << "robot: " << yamlString(model.name()) << "\n";
  out << "root_link: " << yamlString(model.rootLink()) << "\n";
  out << "links:\n";
  for (const auto& link : model.links()) {
    out << "- {name: " << yamlString(link.name) << ", parent_joint: "
        << (link.parent_joint < 0 ? std::string("null") : yamlString(model.joints()[link.parent_joint].name))
        << ", geometry: " << (link.collision.shapes.empty() ? "false" : "true") << ", shapes: " << shapesYaml(link)
        << "}\n";
  }
  out << "joints:\n";
  for (const auto& joint : model.joints()) {
    out << "- name: " << yamlString(joint.name) << "\n";
    out << "  type: " << toString(joint.type) << "\n";
    out << "  parent: " << yamlString(joint.parent_link) << "\n";
    out << "  child: " << yamlString(joint.child_link) << "\n";
    out << "  xyz: " << yamlVector(joint.origin.translation()) << "\n";
    out << "  rpy: " << yamlVector(rpyOf(joint.origin.linear())) << "\n";
    out << "  axis: " << yamlVector(joint.axis) << "\n";
    out << "  active: " << (joint.isActive() ? "true" : "false") << "\n";
    if (joint.type != JointType::kFixed) {
      out << "  bounded: " << (joint.limits.bounded ? "true" : "false") << "\n";
      out << "  lower: " << yamlNumber(joint.limits.lower) << "\n";
      out << "  upper: " << yamlNumber(joint.limits.upper) << "\n";
      out << "  velocity: " << yamlNumber(joint.limits.velocity) << "\n";
      out << "  effort: " << yamlNumber(joint.limits.effort) << "\n";
    }
    if (joint.mimic) {
      out << "  mimic: {joint: " << yamlString(joint.mimic->joint) << ", multiplier: "
          << yamlNumber(joint.mimic->multiplier) << ", offset: " << yamlNumber(joint.mimic->offset) << "}\n";
    }
  }
  out << "groups:\n";
  for (const auto& group : model.groups()) {
    out << "- name: " << yamlString(group.name) << "\n";
    out << "  joints: " << yamlNames(group.joints) << "\n";
    out << "  active_joints: " << yamlNames(group.active_joints) << "\n";
    out << "  links: " << yamlNames(group.links) << "\n";
    out << "  chain: " << (group.isChain() ? "true" : "false") << "\n";
    if (group.isChain()) {
      out << "  base_link: " << yamlString(group.chain_base) << "\n";
      out << "  tip_link: " << yamlString(group.chain_tip) << "\n";
    }
    // The solver that fits: the closed form where the chain's geometry allows it (what createIkSolver
    // would build from kinematics.yaml), else the numeric solver; the reason is the analytic solver's own.
    std::string solver = "none";
    std::string reason;
    try {
      createIkSolver("analytic", model, group.name);
      solver = "analytic";
      reason = "6R chain with a spherical wrist: closed-form IK (all solutions)";
    } catch (const AnalyticIkUnsupported& e) {
      solver = "numeric";
      reason = std::string("no closed form: ") + e.what();
    } catch (const std::exception& e) {
      reason = std::string("no IK: ") + e.what();
    }
    out << "  solver: " << solver << "\n";
    out << "  solver_reason: " << yamlString(reason) << "\n";
  }
  out << "group_states:\n";
  for (const auto& state : model.groupStates()) {
    out << "- name: " << yamlString(state.name) << "\n  group: " << yamlString(state.group) << "\n  values: {";
    bool first = true;
    for (const auto& [joint, value] : state.values) {
      out << (first ? "" : ", ") << yamlString(joint) << ": " << yamlNumber(value);
      first = false;
    }
    out << "}\n";
  }
  out << "end_effectors:\n";
  for (const auto& ee : model.endEffectors()) {
    out << "- {name: " << yamlString(ee.name) << ", parent_link: " << yamlString(ee.parent_link)
        << ", group: " << yamlString(ee.group) << ", parent_group: " << yamlString(ee.parent_group) << "}\n";
  }
  out << "virtual_joints:\n";
  for (const auto& vj : model.virtualJoints()) {
    out << "- {name: " << yamlString(vj.name) << ", type: " << yamlString(vj.type)
        << ", parent_frame: " << yamlString(vj.parent_frame) << ", child_link: " << yamlString(vj.child_link)
        << "}\n";
  }
  const auto conflicts = mimicLimitConflicts(model);
  out << "mimic_limit_conflicts:" << (conflicts.empty() ? " []" : "") << "\n";
  for (const auto& c : conflicts) {
    out << "- {joint: " << yamlString(c.joint) << ", master: " << yamlString(c.master) << ", range: ["
        << yamlNumber(c.from) << ", " << yamlNumber(c.to) << "], limits: [" << yamlNumber(c.lower) << ", "
        << yamlNumber(c.upper) << "]}\n";
  }
  if (collisions) {
    std::map<std::string, size_t> counts;
    for (const auto& pair : collisions->disabled) ++counts[reasonName(pair.reason)];
    out << "collisions: {link_pairs: " << collisions->link_pairs << ", samples: " << collisions->samples
        << ", pair_checks: " << collisions->pair_checks << ", Adjacent: " << counts["Adjacent"]
        << ", Default: " << counts["Default"] << ", Always: " << counts["Always"] << ", Never: " << counts["Never"]
        << ", Gripper: " << counts["Gripper"] << ", enabled: " << collisions->link_pairs - collisions->disabled.size() << "}\n";
  }
  return out.str();
}

}  // namespace sixdof_core
