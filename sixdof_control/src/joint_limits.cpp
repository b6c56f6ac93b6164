#include "sixdof_control/joint_limits.h"

#include <cmath>
#include <set>
#include <stdexcept>

namespace sixdof_control {
namespace {

double number(const YAML::Node& node, const std::string& where) {
  try {
    const double v = node.as<double>();
    if (std::isfinite(v)) return v;
  } catch (const YAML::Exception&) {
  }
  throw std::invalid_argument("joint_limits: " + where + " must be a finite number");
}

bool flag(const YAML::Node& node, const std::string& where) {
  try {
    return node.as<bool>();
  } catch (const YAML::Exception&) {
    throw std::invalid_argument("joint_limits: " + where + " must be true or false");
  }
}

}  // namespace

std::vector<JointLimit> loadJointLimits(const sixdof_core::RobotModel& model, const YAML::Node& joint_limits,
                                        const std::vector<std::string>& joints) {
  static const std::set<std::string> kKeys = {"has_position_limits", "min_position",      "max_position",
                                              "has_velocity_limits", "max_velocity",      "has_acceleration_limits",
                                              "max_acceleration",    "has_effort_limits", "max_effort"};
  if (joint_limits && !joint_limits.IsNull() && !joint_limits.IsMap()) {
    throw std::invalid_argument("joint_limits: the file must be a mapping");
  }
  const YAML::Node table = joint_limits && joint_limits.IsMap() ? joint_limits["joint_limits"] : YAML::Node();
  if (table && !table.IsNull() && !table.IsMap()) throw std::invalid_argument("joint_limits: must be a mapping");
  std::vector<JointLimit> out;
  for (const std::string& joint : joints) {
    if (model.jointIndex(joint) < 0) {
      throw std::invalid_argument("joint_limits: joint '" + joint + "' is not in the robot model");
    }
    const sixdof_core::JointModel& urdf = model.joint(joint);
    JointLimit l;
    l.joint = joint;
    l.has_position_limits = urdf.limits.bounded && urdf.type != sixdof_core::JointType::kContinuous;
    l.min_position = urdf.limits.lower;
    l.max_position = urdf.limits.upper;
    l.has_velocity_limits = urdf.limits.velocity > 0.0;
    l.max_velocity = urdf.limits.velocity;
    const YAML::Node entry = table && table.IsMap() ? table[joint] : YAML::Node();
    if (entry && entry.IsMap()) {
      for (const auto& kv : entry) {
        const std::string key = kv.first.as<std::string>();
        if (kKeys.count(key) == 0) {
          throw std::invalid_argument("joint_limits: unknown key '" + key + "' for joint '" + joint + "'");
        }
      }
      const std::string at = "joint_limits/" + joint + "/";
      if (entry["has_position_limits"]) {
        l.has_position_limits = flag(entry["has_position_limits"], at + "has_position_limits");
        if (l.has_position_limits) {
          if (entry["min_position"]) l.min_position = number(entry["min_position"], at + "min_position");
          if (entry["max_position"]) l.max_position = number(entry["max_position"], at + "max_position");
        }
      }
      if (entry["has_velocity_limits"]) {
        l.has_velocity_limits = flag(entry["has_velocity_limits"], at + "has_velocity_limits");
        if (l.has_velocity_limits && entry["max_velocity"]) {
          l.max_velocity = number(entry["max_velocity"], at + "max_velocity");
        }
      }
    } else if (entry && !entry.IsNull()) {
      throw std::invalid_argument("joint_limits: joint_limits/" + joint + " must be a mapping");
    }
    if (l.has_position_limits && l.min_position > l.max_position) {
      throw std::invalid_argument("joint_limits: joint '" + joint + "' has min_position above max_position");
    }
    if (l.has_velocity_limits && !(l.max_velocity > 0.0)) {
      throw std::invalid_argument("joint_limits: joint '" + joint + "' has a velocity limit that is not > 0");
    }
    out.push_back(l);
  }
  return out;
}

}  // namespace sixdof_control
