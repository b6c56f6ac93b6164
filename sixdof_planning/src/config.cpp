#include "sixdof_planning/config.h"

#include <cmath>
#include <set>

#include <xmlrpcpp/XmlRpcValue.h>

namespace sixdof_planning {

namespace {

std::string fullName(const ros::NodeHandle& nh, const std::string& key) { return nh.resolveName(key); }

std::string requireString(const ros::NodeHandle& nh, const std::string& key) {
  std::string value;
  if (!nh.hasParam(key)) throw ConfigError("missing parameter " + fullName(nh, key));
  if (!nh.getParam(key, value)) throw ConfigError("parameter " + fullName(nh, key) + " is not a string");
  if (value.empty()) throw ConfigError("parameter " + fullName(nh, key) + " is empty");
  return value;
}

double toDouble(const XmlRpc::XmlRpcValue& value, const std::string& name) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(value);
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(value);
  throw ConfigError("parameter " + name + " is not a number");
}

bool toBool(const XmlRpc::XmlRpcValue& value, const std::string& name) {
  if (value.getType() != XmlRpc::XmlRpcValue::TypeBoolean) throw ConfigError("parameter " + name + " is not a bool");
  return static_cast<bool>(const_cast<XmlRpc::XmlRpcValue&>(value));
}

std::string toString(const XmlRpc::XmlRpcValue& value, const std::string& name) {
  if (value.getType() != XmlRpc::XmlRpcValue::TypeString) throw ConfigError("parameter " + name + " is not a string");
  return static_cast<std::string>(const_cast<XmlRpc::XmlRpcValue&>(value));
}

double positiveParam(const ros::NodeHandle& nh, const std::string& key, double default_value, bool allow_zero) {
  double value = default_value;
  if (nh.hasParam(key) && !nh.getParam(key, value)) {
    throw ConfigError("parameter " + fullName(nh, key) + " is not a number");
  }
  if (!std::isfinite(value) || value < 0.0 || (!allow_zero && value == 0.0)) {
    throw ConfigError("parameter " + fullName(nh, key) + " must be " + (allow_zero ? ">= 0" : "> 0") + ", got " +
                      std::to_string(value));
  }
  return value;
}

// Calls visit(prefix, entry) for each entry of the list parameter `name`, prefix naming it ("<name>[<i>]"): the
// parameter must be a list of dictionaries.
template <class Visit>
void forEachDictionary(XmlRpc::XmlRpcValue& list, const std::string& name, Visit visit) {
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("parameter " + name + " must be a list");
  for (int i = 0; i < list.size(); ++i) {
    const std::string prefix = name + "[" + std::to_string(i) + "]";
    auto& entry = list[i];
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct) throw ConfigError(prefix + " must be a dictionary");
    visit(prefix, entry);
  }
}

void loadKinematics(const ros::NodeHandle& nh, MoveGroupConfig* config) {
  const std::string root = "robot_description_kinematics";
  XmlRpc::XmlRpcValue groups;
  if (!nh.getParam(root, groups)) return;  // no IK configured: pose goals then fail with a clear message
  if (groups.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    throw ConfigError("parameter " + fullName(nh, root) + " must be a dictionary of groups");
  }
  for (auto& entry : groups) {
    const std::string prefix = fullName(nh, root) + "/" + entry.first;
    if (entry.second.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      throw ConfigError("parameter " + prefix + " must be a dictionary");
    }
    GroupKinematicsConfig group;
    auto& values = entry.second;
    if (!values.hasMember("kinematics_solver")) throw ConfigError("missing parameter " + prefix + "/kinematics_solver");
    for (auto& field : values) {
      const std::string name = prefix + "/" + field.first;
      if (field.first == "kinematics_solver") {
        group.solver = toString(field.second, name);
      } else if (field.first == "kinematics_solver_search_resolution") {
        group.search_resolution = toDouble(field.second, name);
      } else if (field.first == "kinematics_solver_timeout") {
        group.timeout = toDouble(field.second, name);
        if (!(group.timeout > 0.0)) throw ConfigError("parameter " + name + " must be > 0");
      } else if (field.first == "kinematics_solver_attempts") {
        group.attempts = static_cast<int>(toDouble(field.second, name));
        if (group.attempts < 1) throw ConfigError("parameter " + name + " must be >= 1");
      } else if (field.first == "position_only_ik") {
        group.position_only = toBool(field.second, name);
      } else {
        throw ConfigError("unknown parameter " + name);
      }
    }
    config->kinematics[entry.first] = group;
  }
}

void loadJointLimits(const ros::NodeHandle& nh, MoveGroupConfig* config) {
  const std::string root = "robot_description_planning/joint_limits";
  XmlRpc::XmlRpcValue joints;
  if (!nh.getParam(root, joints)) return;  // URDF velocity limits only; checkConfig names what is missing
  if (joints.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    throw ConfigError("parameter " + fullName(nh, root) + " must be a dictionary of joints");
  }
  for (auto& entry : joints) {
    const std::string prefix = fullName(nh, root) + "/" + entry.first;
    auto& values = entry.second;
    if (values.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      throw ConfigError("parameter " + prefix + " must be a dictionary");
    }
    JointLimitConfig limits;
    auto flag = [&](const char* key) { return values.hasMember(key) && toBool(values[key], prefix + "/" + key); };
    auto number = [&](const char* key) {
      if (!values.hasMember(key)) throw ConfigError("missing parameter " + prefix + "/" + key);
      const double v = toDouble(values[key], prefix + "/" + key);
      if (!std::isfinite(v) || v <= 0.0) throw ConfigError("parameter " + prefix + "/" + key + " must be > 0");
      return v;
    };
    if (flag("has_velocity_limits")) limits.max_velocity = number("max_velocity");
    if (flag("has_acceleration_limits")) limits.max_acceleration = number("max_acceleration");
    config->joint_limits[entry.first] = limits;
  }
}

void loadControllers(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, MoveGroupConfig* config) {
  // MoveIt loads controller_list into move_group's private namespace; a shared controllers.yaml puts it in
  // the node's namespace.
  const ros::NodeHandle& source = private_nh.hasParam("controller_list") ? private_nh : nh;
  const std::string name = fullName(source, "controller_list");
  XmlRpc::XmlRpcValue list;
  if (!source.getParam("controller_list", list)) {
    throw ConfigError("missing parameter controller_list (looked for " + fullName(private_nh, "controller_list") +
                      " and " + fullName(nh, "controller_list") + ")");
  }
  forEachDictionary(list, name, [&](const std::string& prefix, XmlRpc::XmlRpcValue& entry) {
    ControllerConfig controller;
    if (!entry.hasMember("name")) throw ConfigError(prefix + " has no name");
    controller.name = toString(entry["name"], prefix + "/name");
    if (entry.hasMember("action_ns")) controller.action_ns = toString(entry["action_ns"], prefix + "/action_ns");
    controller.type = entry.hasMember("type") ? toString(entry["type"], prefix + "/type") : "FollowJointTrajectory";
    if (controller.type != "FollowJointTrajectory") {
      throw ConfigError(prefix + "/type '" + controller.type + "' is not supported (FollowJointTrajectory is)");
    }
    if (!entry.hasMember("joints") || entry["joints"].getType() != XmlRpc::XmlRpcValue::TypeArray ||
        entry["joints"].size() == 0) {
      throw ConfigError(prefix + "/joints must be a non-empty list");
    }
    for (int j = 0; j < entry["joints"].size(); ++j) {
      controller.joints.push_back(toString(entry["joints"][j], prefix + "/joints[" + std::to_string(j) + "]"));
    }
    config->controllers.push_back(controller);
  });
}

void loadOccupancyMap(const ros::NodeHandle& private_nh, OccupancyMapConfig* config) {
  if (private_nh.hasParam("octomap_frame") && !private_nh.getParam("octomap_frame", config->octomap_frame)) {
    throw ConfigError("parameter " + fullName(private_nh, "octomap_frame") + " is not a string");
  }
  config->octomap_resolution = positiveParam(private_nh, "octomap_resolution", config->octomap_resolution, false);
  config->max_range = positiveParam(private_nh, "max_range", config->max_range, false);
  XmlRpc::XmlRpcValue list;
  if (!private_nh.getParam("sensors", list)) return;
  const std::string name = fullName(private_nh, "sensors");
  forEachDictionary(list, name, [&](const std::string& prefix, XmlRpc::XmlRpcValue& entry) {
    OctomapSensorConfig sensor;
    sensor.max_range = config->max_range;
    auto number = [&](const std::string& key, bool allow_zero) {
      const double v = toDouble(entry[key], prefix + "/" + key);
      if (!std::isfinite(v) || v < 0.0 || (!allow_zero && v == 0.0)) {
        throw ConfigError("parameter " + prefix + "/" + key + " must be " + (allow_zero ? ">= 0" : "> 0") + ", got " +
                          std::to_string(v));
      }
      return v;
    };
    for (auto& field : entry) {
      const std::string& key = field.first;
      if (key == "sensor_plugin") {
        sensor.sensor_plugin = toString(field.second, prefix + "/" + key);
      } else if (key == "point_cloud_topic") {
        sensor.point_cloud_topic = toString(field.second, prefix + "/" + key);
      } else if (key == "filtered_cloud_topic") {
        sensor.filtered_cloud_topic = toString(field.second, prefix + "/" + key);
      } else if (key == "max_range") {
        sensor.max_range = number(key, false);
      } else if (key == "padding_offset") {
        sensor.padding_offset = number(key, true);
      } else if (key == "padding_scale") {
        sensor.padding_scale = number(key, false);
      } else if (key == "max_update_rate") {
        sensor.max_update_rate = number(key, true);
      } else if (key == "point_subsample") {
        const double v = number(key, false);
        if (v != std::floor(v)) throw ConfigError("parameter " + prefix + "/" + key + " must be an integer >= 1");
        sensor.point_subsample = static_cast<int>(v);
      } else {
        throw ConfigError("unknown parameter " + prefix + "/" + key);
      }
    }
    if (sensor.sensor_plugin.empty()) throw ConfigError("missing parameter " + prefix + "/sensor_plugin");
    if (sensor.sensor_plugin != "occupancy_map_monitor/PointCloudOctomapUpdater") {
      throw ConfigError("parameter " + prefix + "/sensor_plugin '" + sensor.sensor_plugin +
                        "' is not supported (occupancy_map_monitor/PointCloudOctomapUpdater is)");
    }
    if (sensor.point_cloud_topic.empty()) throw ConfigError("missing parameter " + prefix + "/point_cloud_topic");
    config->sensors.push_back(sensor);
  });
}

}  // namespace

MoveGroupConfig loadConfig(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh) {
  MoveGroupConfig config;
  config.urdf = requireString(nh, "robot_description");
  config.srdf = requireString(nh, "robot_description_semantic");
  if (nh.hasParam("robot_description_grasping")) config.grasping_yaml = requireString(nh, "robot_description_grasping");
  loadKinematics(nh, &config);
  loadJointLimits(nh, &config);
  config.default_robot_padding =
      positiveParam(nh, "robot_description_planning/default_robot_padding", config.default_robot_padding, true);
  loadControllers(nh, private_nh, &config);
  config.default_planning_time =
      positiveParam(private_nh, "default_planning_time", config.default_planning_time, false);
  if (private_nh.hasParam("default_planner_id") &&
      !private_nh.getParam("default_planner_id", config.default_planner_id)) {
    throw ConfigError("parameter " + fullName(private_nh, "default_planner_id") + " is not a string");
  }
  config.execution_duration_scaling =
      positiveParam(private_nh, "allowed_execution_duration_scaling", config.execution_duration_scaling, false);
  config.execution_goal_margin =
      positiveParam(private_nh, "allowed_goal_duration_margin", config.execution_goal_margin, true);
  config.start_state_tolerance =
      positiveParam(private_nh, "allowed_start_tolerance", config.start_state_tolerance, true);
  config.execution_watchdog_timeout =
      positiveParam(private_nh, "execution_watchdog_timeout", config.execution_watchdog_timeout, false);
  config.start_state_max_bounds_error =
      positiveParam(private_nh, "start_state_max_bounds_error", config.start_state_max_bounds_error, true);
  config.joint_state_timeout = positiveParam(private_nh, "joint_state_timeout", config.joint_state_timeout, true);
  config.longest_valid_segment_fraction = positiveParam(private_nh, "longest_valid_segment_fraction",
                                                        config.longest_valid_segment_fraction, false);
  if (config.longest_valid_segment_fraction > 1.0) {
    throw ConfigError("parameter " + fullName(private_nh, "longest_valid_segment_fraction") + " must be <= 1, got " +
                      std::to_string(config.longest_valid_segment_fraction));
  }
  if (private_nh.hasParam("simplify_solutions") &&
      !private_nh.getParam("simplify_solutions", config.simplify_solutions)) {
    throw ConfigError("parameter " + fullName(private_nh, "simplify_solutions") + " is not a bool");
  }
  config.trajectory_sample_period =
      positiveParam(private_nh, "trajectory_sample_period", config.trajectory_sample_period, false);
  loadOccupancyMap(private_nh, &config.occupancy_map);
  return config;
}

void checkConfig(const sixdof_core::RobotModel& model, MoveGroupConfig* config) {
  for (const auto& entry : config->kinematics) {
    const auto* group = model.findGroup(entry.first);
    if (!group) throw ConfigError("robot_description_kinematics names unknown group '" + entry.first + "'");
    const std::string& solver = entry.second.solver;
    if (solver != "analytic" && solver != "kdl" && solver != "numeric") {
      throw ConfigError("robot_description_kinematics/" + entry.first + "/kinematics_solver '" + solver +
                        "' is not one of analytic, kdl, numeric");
    }
  }
  for (const auto& entry : config->joint_limits) {
    if (model.jointIndex(entry.first) < 0) {
      throw ConfigError("robot_description_planning/joint_limits names unknown joint '" + entry.first + "'");
    }
  }
  for (const auto& name : model.variableNames()) {
    JointLimitConfig& limits = config->joint_limits[name];
    if (limits.max_velocity <= 0.0) limits.max_velocity = model.joint(name).limits.velocity;
    if (limits.max_velocity <= 0.0) {
      throw ConfigError("joint '" + name + "' has no velocity limit (URDF or robot_description_planning/joint_limits)");
    }
    if (limits.max_acceleration <= 0.0) {
      throw ConfigError("joint '" + name +
                        "' has no acceleration limit (robot_description_planning/joint_limits/" + name +
                        "/max_acceleration)");
    }
  }
  std::set<std::string> taken;
  for (const auto& controller : config->controllers) {
    for (const auto& joint : controller.joints) {
      if (model.jointIndex(joint) < 0) {
        throw ConfigError("controller '" + controller.name + "' names unknown joint '" + joint + "'");
      }
      if (!taken.insert(joint).second) {
        throw ConfigError("joint '" + joint + "' is listed by more than one controller (second: '" +
                          controller.name + "')");
      }
    }
  }
  if (!config->grasping_yaml.empty()) {
    config->grasping = parseGraspingConfig(config->grasping_yaml, model, "parameter robot_description_grasping");
  }
}

}  // namespace sixdof_planning
