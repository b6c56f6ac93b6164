#include "sixdof_planning/grasping_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <sixdof_core/kinematics.h>

#include "sixdof_planning/config.h"

namespace sixdof_planning {

namespace {

const std::set<std::string> kKeys = {"group",        "end_effector",      "tcp",          "open",
                                     "closed",       "max_opening",       "closed_width", "finger_reach",
                                     "palm_depth",   "pad_links",         "grasp_fix",    "closing_direction",
                                     "approach_direction", "suction"};
const std::set<std::string> kSuctionKeys = {"cup_link",         "max_payload", "tilt_tolerance",
                                            "contact_distance", "controller",  "arm_name"};
const std::set<std::string> kTcpKeys = {"frame", "parent_link", "xyz", "rpy", "source"};
const std::set<std::string> kStateKeys = {"state", "positions"};

// Reads one grasping.yaml against a model; every message names the source and the key.
class Reader {
 public:
  Reader(const sixdof_core::RobotModel& model, std::string source) : model_(model), source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(source_ + ": '" + key + "' " + what);
  }

  YAML::Node map(const YAML::Node& node, const std::string& key, const std::set<std::string>& keys) const {
    if (!node.IsMap()) fail(key, "must be a mapping");
    for (const auto& entry : node) {
      const std::string name = entry.first.as<std::string>();
      if (!keys.count(name)) fail(key.empty() ? name : key + "." + name, "is not a key of grasping.yaml");
    }
    return node;
  }

  YAML::Node required(const YAML::Node& parent, const std::string& prefix, const std::string& key) const {
    const YAML::Node node = parent[key];
    if (!node) fail(prefix + key, "is missing");
    return node;
  }

  std::string string(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(key, "must be a string");
    return node.as<std::string>();
  }

  double number(const YAML::Node& node, const std::string& key) const {
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || std::isnan(value)) {
      fail(key, "must be a number");
    }
    return value;
  }

  double finite(const YAML::Node& node, const std::string& key, double lower, bool allow_lower) const {
    const double value = number(node, key);
    if (!std::isfinite(value) || value < lower || (!allow_lower && value == lower)) {
      fail(key, std::string("must be a finite number ") + (allow_lower ? ">= " : "> ") + std::to_string(lower));
    }
    return value;
  }

  Eigen::Vector3d vector(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(key, "must be a list of 3 numbers");
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      v[i] = number(node[i], key);
      if (!std::isfinite(v[i])) fail(key, "must be a list of 3 finite numbers");
    }
    return v;
  }

  Eigen::Vector3d direction(const YAML::Node& node, const std::string& key) const {
    const Eigen::Vector3d v = vector(node, key);
    if (v.norm() < 1e-9) fail(key, "must not be zero");
    return v.normalized();
  }

  std::string link(const YAML::Node& node, const std::string& key) const {
    const std::string name = string(node, key);
    if (model_.linkIndex(name) < 0) fail(key, "names link '" + name + "', which the URDF does not have");
    return name;
  }

  GripperState state(const YAML::Node& node, const std::string& key, const sixdof_core::JointGroup& group) const {
    map(node, key, kStateKeys);
    GripperState out;
    out.name = string(required(node, key + ".", "state"), key + ".state");
    const YAML::Node positions = required(node, key + ".", "positions");
    if (!positions.IsMap()) fail(key + ".positions", "must be a mapping of joint names to positions");
    for (const auto& entry : positions) {
      const std::string joint = entry.first.as<std::string>();
      const std::string where = key + ".positions." + joint;
      if (std::find(group.active_joints.begin(), group.active_joints.end(), joint) == group.active_joints.end()) {
        fail(where, "is not an actuated joint of group '" + group.name + "' (mimic joints follow their master)");
      }
      const double value = number(entry.second, where);
      const auto& limits = model_.joint(joint).limits;
      if (!std::isfinite(value) || (limits.bounded && (value < limits.lower || value > limits.upper))) {
        fail(where, "= " + std::to_string(value) + " is outside the joint's limits [" + std::to_string(limits.lower) +
                        ", " + std::to_string(limits.upper) + "]");
      }
      out.positions[joint] = value;
    }
    for (const auto& joint : group.active_joints) {
      if (!out.positions.count(joint)) fail(key + ".positions", "has no position of joint '" + joint + "'");
    }
    // The SRDF's group state of that name, where there is one, must say the same.
    if (const auto* srdf = model_.findGroupState(group.name, out.name)) {
      for (const auto& [joint, value] : out.positions) {
        const auto it = srdf->values.find(joint);
        if (it != srdf->values.end() && std::abs(it->second - value) > 1e-9) {
          fail(key + ".positions." + joint, "= " + std::to_string(value) + " disagrees with the SRDF's state '" +
                                                out.name + "' of group '" + group.name + "' (" +
                                                std::to_string(it->second) + ")");
        }
      }
    }
    return out;
  }

  // The pose of `frame` in `parent` when only fixed joints lead down from parent to frame.
  bool fixedBelow(const std::string& parent, const std::string& frame, Eigen::Isometry3d* pose) const {
    *pose = Eigen::Isometry3d::Identity();
    int index = model_.linkIndex(frame);
    while (index >= 0 && model_.links()[index].name != parent) {
      const auto& link = model_.links()[index];
      if (link.parent_joint < 0) return false;
      const auto& joint = model_.joints()[link.parent_joint];
      if (joint.type != sixdof_core::JointType::kFixed) return false;
      *pose = joint.origin * *pose;
      index = link.parent_link;
    }
    return index >= 0;
  }

 private:
  const sixdof_core::RobotModel& model_;
  std::string source_;
};

}  // namespace

GraspingConfig parseGraspingConfig(const std::string& yaml_text, const sixdof_core::RobotModel& model,
                                   const std::string& source) {
  YAML::Node loaded;
  try {
    loaded = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not valid YAML: " + e.msg);
  }
  const YAML::Node root = loaded;  // read-only: operator[] must not add the keys it looks for
  const Reader read(model, source);
  if (!root.IsMap()) throw ConfigError(source + ": must be a YAML mapping (grasping.yaml)");
  try {
    read.map(root, "", kKeys);
    GraspingConfig config;
    config.group = read.string(read.required(root, "", "group"), "group");
    const sixdof_core::JointGroup* group = model.findGroup(config.group);
    if (group == nullptr) read.fail("group", "names group '" + config.group + "', which the SRDF does not have");

    std::string eef_name;
    if (root["end_effector"]) eef_name = read.string(root["end_effector"], "end_effector");
    const auto& eefs = model.endEffectors();
    const auto eef = std::find_if(eefs.begin(), eefs.end(), [&](const sixdof_core::EndEffector& e) {
      return eef_name.empty() ? e.group == group->name : e.name == eef_name;
    });
    if (eef == eefs.end() || eef->group != group->name) {
      read.fail(eef_name.empty() ? "group" : "end_effector",
                "has no SRDF end effector of group '" + group->name + "'" +
                    (eef_name.empty() ? "" : " named '" + eef_name + "'"));
    }
    config.end_effector = eef->name;

    const YAML::Node tcp = read.map(read.required(root, "", "tcp"), "tcp", kTcpKeys);
    config.parent_link = read.link(read.required(tcp, "tcp.", "parent_link"), "tcp.parent_link");
    if (config.parent_link != eef->parent_link) {
      read.fail("tcp.parent_link", "is '" + config.parent_link + "', not the parent link '" + eef->parent_link +
                                       "' of end effector '" + eef->name + "'");
    }
    const Eigen::Vector3d xyz = read.vector(read.required(tcp, "tcp.", "xyz"), "tcp.xyz");
    const Eigen::Vector3d rpy = read.vector(read.required(tcp, "tcp.", "rpy"), "tcp.rpy");
    config.tcp = sixdof_core::poseFromXyzRpy(xyz.x(), xyz.y(), xyz.z(), rpy.x(), rpy.y(), rpy.z());
    if (tcp["frame"]) config.tcp_frame = read.string(tcp["frame"], "tcp.frame");
    Eigen::Isometry3d frame_pose;
    if (!config.tcp_frame.empty() && model.linkIndex(config.tcp_frame) >= 0) {
      if (!read.fixedBelow(config.parent_link, config.tcp_frame, &frame_pose) ||
          !frame_pose.isApprox(config.tcp, 1e-6)) {
        read.fail("tcp.frame", "is the URDF's link '" + config.tcp_frame + "', which is not fixed at tcp.xyz/rpy below '" +
                                   config.parent_link + "'");
      }
    }

    config.approach_direction =
        read.direction(read.required(root, "", "approach_direction"), "approach_direction");
    if (root["suction"]) {
      const YAML::Node suction = read.map(root["suction"], "suction", kSuctionKeys);
      config.suction_cup = read.link(read.required(suction, "suction.", "cup_link"), "suction.cup_link");
      config.vacuum_controller =
          suction["controller"] ? read.string(suction["controller"], "suction.controller") : "gripper_controller";
      config.max_payload =
          suction["max_payload"] ? read.finite(suction["max_payload"], "suction.max_payload", 0.0, false) : 0.5;
      return config;
    }
    config.open = read.state(read.required(root, "", "open"), "open", *group);
    config.closed = read.state(read.required(root, "", "closed"), "closed", *group);
    config.max_opening = read.finite(read.required(root, "", "max_opening"), "max_opening", 0.0, false);
    if (root["closed_width"]) {
      config.closed_width = read.finite(root["closed_width"], "closed_width", -config.max_opening, true);
    }
    if (root["finger_reach"]) {
      config.finger_reach = read.number(root["finger_reach"], "finger_reach");
      if (!std::isfinite(config.finger_reach)) read.fail("finger_reach", "must be a finite number");
    }
    config.palm_depth = std::numeric_limits<double>::infinity();
    if (root["palm_depth"]) {
      config.palm_depth = read.number(root["palm_depth"], "palm_depth");
      if (!(config.palm_depth > 0.0)) read.fail("palm_depth", "must be > 0 (.inf: no palm across the pads)");
    }
    if (root["pad_links"]) {
      const YAML::Node pads = root["pad_links"];
      if (!pads.IsSequence() || (pads.size() != 0 && pads.size() != 2)) {
        read.fail("pad_links", "must be a list of two link names (or empty)");
      }
      for (const auto& pad : pads) config.pad_links.push_back(read.link(pad, "pad_links"));
    }
    config.closing_direction =
        read.direction(read.required(root, "", "closing_direction"), "closing_direction");
    return config;
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": " + e.msg);
  }
}

}  // namespace sixdof_planning
