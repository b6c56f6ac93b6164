#include "sixdof_control/controller_params.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sixdof_control {

using sixdof_core::GripperControllerConfig;
using sixdof_core::TrajectoryControllerConfig;

namespace {

double readDouble(const ros::NodeHandle& nh, const std::string& key, double fallback) {
  if (!nh.hasParam(key)) return fallback;
  double value = 0.0;
  if (!nh.getParam(key, value)) throw std::runtime_error("parameter '" + nh.resolveName(key) + "' must be a number");
  return value;
}

template <class T>
void readPrivate(const ros::NodeHandle& pnh, const std::string& key, T* value) {
  if (pnh.hasParam(key) && !pnh.getParam(key, *value)) {
    throw std::runtime_error("parameter '" + pnh.resolveName(key) + "' has the wrong type");
  }
}

const RobotJoint& findJoint(const std::vector<RobotJoint>& joints, const std::string& name, const std::string& who) {
  for (const RobotJoint& j : joints) {
    if (j.name == name) return j;
  }
  throw std::runtime_error(who + ": joint '" + name + "' is not an actuated joint of the robot");
}

TrajectoryControllerConfig readTrajectoryControllerConfig(const ros::NodeHandle& nh, const std::string& name,
                                                          const std::vector<RobotJoint>& robot) {
  const std::string who = "controller '" + nh.resolveName(name) + "'";
  std::string type;
  if (!nh.getParam(name + "/type", type)) {
    throw std::runtime_error(who + ": no 'type' parameter (is the controllers config loaded?)");
  }
  const std::string suffix = "JointTrajectoryController";
  if (type.size() < suffix.size() || type.compare(type.size() - suffix.size(), suffix.size(), suffix) != 0) {
    throw std::runtime_error(who + ": type '" + type + "' is not supported (only *JointTrajectoryController)");
  }
  TrajectoryControllerConfig c;
  c.name = name;
  if (!nh.getParam(name + "/joints", c.joints) || c.joints.empty()) {
    throw std::runtime_error(who + ": 'joints' must be a non-empty list of joint names");
  }
  const std::string cons = name + "/constraints/";
  c.goal_time = readDouble(nh, cons + "goal_time", 0.0);
  c.stopped_velocity_tolerance = readDouble(nh, cons + "stopped_velocity_tolerance", 0.01);
  for (const std::string& j : c.joints) {
    const RobotJoint& info = findJoint(robot, j, who);
    // Continuous joints (bounded = false) have no position limit to check.
    c.lower_limits.push_back(info.bounded ? info.lower : -std::numeric_limits<double>::infinity());
    c.upper_limits.push_back(info.bounded ? info.upper : std::numeric_limits<double>::infinity());
    c.path_tolerance.push_back(readDouble(nh, cons + j + "/trajectory", 0.0));
    c.goal_tolerance.push_back(readDouble(nh, cons + j + "/goal", 0.0));
  }
  return c;
}

// <name>/state_publish_rate (Hz, default 50 as joint_trajectory_controller; 0 = no state topic).
double readStatePublishRate(const ros::NodeHandle& nh, const std::string& name) {
  const double rate = readDouble(nh, name + "/state_publish_rate", 50.0);
  if (!std::isfinite(rate) || rate < 0.0) {
    throw std::runtime_error("parameter '" + nh.resolveName(name + "/state_publish_rate") +
                             "' must be >= 0 (Hz; 0 = no state topic), got " + std::to_string(rate));
  }
  return rate;
}

// The names in `controller_list` (moveit_simple_controller_manager's format, from the same controllers config as
// the controllers themselves). Every entry must be a FollowJointTrajectory controller on `follow_joint_trajectory`.
std::vector<std::string> readControllerList(const ros::NodeHandle& nh) {
  const std::string name = nh.resolveName("controller_list");
  XmlRpc::XmlRpcValue list;
  if (!nh.getParam("controller_list", list)) {
    throw std::runtime_error("no parameter '" + name +
                             "' (the controllers config lists the controllers to run; or set ~controllers)");
  }
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) {
    throw std::runtime_error("parameter '" + name + "' must be a list");
  }
  const auto text = [](XmlRpc::XmlRpcValue& entry, const std::string& key) {
    return entry.hasMember(key) && entry[key].getType() == XmlRpc::XmlRpcValue::TypeString
               ? static_cast<std::string>(entry[key])
               : std::string();
  };
  std::vector<std::string> names;
  for (int i = 0; i < list.size(); ++i) {
    const std::string who = name + "[" + std::to_string(i) + "]";
    XmlRpc::XmlRpcValue& entry = list[i];
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct || text(entry, "name").empty()) {
      throw std::runtime_error(who + " must be a dictionary with a 'name'");
    }
    const std::string type = entry.hasMember("type") ? text(entry, "type") : "FollowJointTrajectory";
    const std::string action_ns = entry.hasMember("action_ns") ? text(entry, "action_ns") : "follow_joint_trajectory";
    if (type != "FollowJointTrajectory" || action_ns != "follow_joint_trajectory") {
      throw std::runtime_error(who + " ('" + text(entry, "name") + "'): type '" + type + "' on '" + action_ns +
                               "' is not served (the controllers serve FollowJointTrajectory on "
                               "follow_joint_trajectory, and gripper_cmd)");
    }
    names.push_back(text(entry, "name"));
  }
  if (names.empty()) throw std::runtime_error("parameter '" + name + "' lists no controller");
  return names;
}

// The first of `controllers` with a `gripper_cmd` block, else `gripper_controller` (the name docs/design.md gives
// that action) if it is one of them, else "" (no gripper).
std::string defaultGripperCommandController(const ros::NodeHandle& nh, const std::vector<std::string>& controllers) {
  for (const std::string& c : controllers) {
    if (nh.hasParam(c + "/gripper_cmd")) return c;
  }
  const bool listed = std::find(controllers.begin(), controllers.end(), "gripper_controller") != controllers.end();
  return listed ? "gripper_controller" : "";
}

// The gripper_cmd action of controller `name` drives its first non-mimic joint.
GripperControllerConfig readGripperControllerConfig(const ros::NodeHandle& nh, const std::string& name,
                                                    const std::vector<RobotJoint>& robot) {
  const std::string who = "controller '" + nh.resolveName(name) + "'";
  std::vector<std::string> joints;
  if (!nh.getParam(name + "/joints", joints))
    throw std::runtime_error(who + ": 'joints' must be a list of joint names");
  GripperControllerConfig c;
  c.name = name;
  for (const std::string& j : joints) {
    const RobotJoint& info = findJoint(robot, j, who);
    if (info.mimic_of.empty()) {
      c.joint = j;
      c.lower = info.lower;
      c.upper = info.upper;
      c.effort_limit = info.max_effort;
      break;
    }
  }
  if (c.joint.empty()) throw std::runtime_error(who + ": no non-mimic joint for gripper_cmd");
  const std::string p = name + "/gripper_cmd/";
  // The sixdof arm's finger travels 4 cm: gripper_action_controller's default goal_tolerance of 0.01 would be a
  // quarter of it, so the default here is the finger's trajectory goal tolerance scale.
  c.goal_tolerance = readDouble(nh, p + "goal_tolerance", 0.002);
  c.stall_velocity_threshold = readDouble(nh, p + "stall_velocity_threshold", 0.001);
  c.stall_timeout = readDouble(nh, p + "stall_timeout", 0.5);
  // Closing on an object is how a gripper grasps, so a stall counts as success by default.
  c.allow_stalling = true;
  if (nh.hasParam(p + "allow_stalling") && !nh.getParam(p + "allow_stalling", c.allow_stalling)) {
    throw std::runtime_error("parameter '" + nh.resolveName(p + "allow_stalling") + "' must be a bool");
  }
  return c;
}

}  // namespace

ControllerSetup readControllerSetup(const ros::NodeHandle& nh, const ros::NodeHandle& pnh,
                                    const std::vector<RobotJoint>& robot) {
  // The controllers config says which controllers exist (controller_list), so any robot's config package runs as
  // it is: no gripper is required.
  std::vector<std::string> names;
  if (pnh.hasParam("controllers")) {
    readPrivate(pnh, "controllers", &names);
  } else {
    names = readControllerList(nh);
  }
  std::string gripper = defaultGripperCommandController(nh, names);
  readPrivate(pnh, "gripper_command_controller", &gripper);
  ControllerSetup setup;
  for (const std::string& name : names) {
    TrajectoryControllerConfig config = readTrajectoryControllerConfig(nh, name, robot);
    ControllerJoints joints(name, config.joints, robot);
    setup.trajectory.push_back({std::move(config), std::move(joints), readStatePublishRate(nh, name)});
  }
  if (!gripper.empty()) setup.gripper = readGripperControllerConfig(nh, gripper, robot);
  return setup;
}

std::string controllerSummary(const ControllerSetup& setup) {
  const std::string gripper = setup.gripper ? setup.gripper->name : "";
  std::string text;
  bool gripper_listed = false;
  for (const TrajectoryControllerSetup& c : setup.trajectory) {
    const bool serves_gripper = c.config.name == gripper;
    gripper_listed = gripper_listed || serves_gripper;
    text += (text.empty() ? "" : ", ") + c.config.name + (serves_gripper ? " (+gripper_cmd)" : "");
  }
  if (!gripper.empty() && !gripper_listed) text += (text.empty() ? "" : ", ") + gripper + " (gripper_cmd only)";
  return text.empty() ? "none" : text;
}

}  // namespace sixdof_control
