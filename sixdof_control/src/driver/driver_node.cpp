#include "driver_node.h"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/console.h>
#include <ros/param.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

#include "param_yaml.h"
#include "sixdof_control/joint_limits.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_control {

namespace {

// The driver's own private parameters; any other private parameter must be a plugin's block (a dictionary).
const std::set<std::string> kSettings = {"plugin",
                                         "rate",
                                         "start_tolerance",
                                         "read_timeout",
                                         "velocity_tolerance",
                                         "statistics_window",
                                         "realtime_priority",
                                         "publish_rate",
                                         "controllers",
                                         "gripper_command_controller"};

void checkPrivateParameters(const ros::NodeHandle& pnh) {
  XmlRpc::XmlRpcValue all;
  if (!ros::param::get(pnh.getNamespace(), all) || all.getType() != XmlRpc::XmlRpcValue::TypeStruct) return;
  for (auto& [key, value] : all) {
    if (kSettings.count(key) == 0 && value.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      throw std::runtime_error("unknown parameter '" + pnh.resolveName(key) +
                               "' (the driver's settings: rate, start_tolerance, read_timeout, velocity_tolerance, "
                               "statistics_window, realtime_priority, publish_rate; a dictionary is a plugin's block)");
    }
  }
}

template <class T>
T read(const ros::NodeHandle& pnh, const std::string& key, T fallback) {
  if (!pnh.hasParam(key)) return fallback;
  T value{};
  if (!pnh.getParam(key, value))
    throw std::runtime_error("parameter '" + pnh.resolveName(key) + "' has the wrong type");
  return value;
}

double positive(const ros::NodeHandle& pnh, const std::string& key, double fallback) {
  const double value = read(pnh, key, fallback);
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::runtime_error("parameter '" + pnh.resolveName(key) + "' must be > 0, got " + std::to_string(value));
  }
  return value;
}

std::vector<RobotJoint> robotJoints(const sixdof_core::RobotModel& model) {
  std::vector<RobotJoint> joints;
  for (const sixdof_core::JointModel& j : model.joints()) {
    if (j.type == sixdof_core::JointType::kFixed) continue;
    RobotJoint r{j.name, j.limits.bounded, j.limits.lower, j.limits.upper, j.limits.effort, "", 1.0, 0.0};
    if (j.mimic) {
      r.mimic_of = j.mimic->joint;
      r.mimic_multiplier = j.mimic->multiplier;
      r.mimic_offset = j.mimic->offset;
    }
    joints.push_back(r);
  }
  return joints;
}

// The actuated joints the controllers command, in the model's order.
std::vector<std::string> hardwareJoints(const ControllerSetup& setup, const std::vector<RobotJoint>& robot) {
  std::set<std::string> used;
  for (const TrajectoryControllerSetup& c : setup.trajectory)
    used.insert(c.joints.actuated().begin(), c.joints.actuated().end());
  if (setup.gripper) used.insert(setup.gripper->joint);
  std::vector<std::string> joints;
  for (const RobotJoint& j : robot) {
    if (used.count(j.name) > 0) joints.push_back(j.name);
  }
  return joints;
}

std::vector<PublishedJoint> publishedJoints(const std::vector<std::string>& hardware,
                                            const std::vector<RobotJoint>& robot) {
  std::vector<PublishedJoint> out;
  for (const RobotJoint& j : robot) {
    const std::string& source = j.mimic_of.empty() ? j.name : j.mimic_of;
    const auto it = std::find(hardware.begin(), hardware.end(), source);
    if (it == hardware.end()) continue;
    out.push_back({j.name, static_cast<std::size_t>(it - hardware.begin()),
                   j.mimic_of.empty() ? 1.0 : j.mimic_multiplier, j.mimic_of.empty() ? 0.0 : j.mimic_offset});
  }
  return out;
}

const char* stateName(LoopState state) {
  switch (state) {
    case LoopState::kStopped:
      return "stopped";
    case LoopState::kRunning:
      return "running";
    case LoopState::kEstop:
      return "e-stop";
    case LoopState::kFault:
      return "fault";
  }
  return "";
}

}  // namespace

DriverNode::DriverNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  checkPrivateParameters(pnh_);
  if (!pnh_.getParam("plugin", plugin_) || plugin_.empty()) {
    throw std::runtime_error("no parameter '" + pnh_.resolveName("plugin") +
                             "': the hardware plugin to load (mock, dynamixel, or <package>/<class>)");
  }
  std::string urdf;
  if (!nh_.getParam("robot_description", urdf) || urdf.empty()) {
    throw std::runtime_error("no URDF in parameter '" + nh_.resolveName("robot_description") + "'");
  }
  const char* package_path = std::getenv("ROS_PACKAGE_PATH");
  const sixdof_core::RobotModel model(
      urdf, "", sixdof_core::PackageResolver::fromRosPackagePath(package_path != nullptr ? package_path : ""));
  const std::vector<RobotJoint> robot = robotJoints(model);
  const ControllerSetup setup = readControllerSetup(nh_, pnh_, robot);
  const std::vector<std::string> joints = hardwareJoints(setup, robot);
  if (joints.empty()) throw std::runtime_error("the controllers command no joint");
  published_ = publishedJoints(joints, robot);

  ControlLoopConfig config;
  config.joints = joints;
  YAML::Node limits(YAML::NodeType::Map);
  limits["joint_limits"] = paramYaml(nh_, "robot_description_planning/joint_limits");
  config.limits = loadJointLimits(model, limits, joints);
  addControllers(setup, config);
  config.rate = positive(pnh_, "rate", config.rate);
  config.start_tolerance = read(pnh_, "start_tolerance", config.start_tolerance);
  config.read_timeout = read(pnh_, "read_timeout", config.read_timeout);
  config.velocity_tolerance = read(pnh_, "velocity_tolerance", config.velocity_tolerance);
  const int window = read(pnh_, "statistics_window", static_cast<int>(config.statistics_window));
  if (window < 1) throw std::runtime_error("parameter '" + pnh_.resolveName("statistics_window") + "' must be >= 1");
  config.statistics_window = static_cast<std::size_t>(window);
  config.realtime_priority = read(pnh_, "realtime_priority", config.realtime_priority);
  const double publish_rate = positive(pnh_, "publish_rate", 100.0);

  hardware_ = loader_.load(plugin_);
  const std::string block = plugin_.substr(plugin_.find('/') == std::string::npos ? 0 : plugin_.rfind('/') + 1);
  const HardwareResult init = hardware_->init(joints, paramYaml(pnh_, block));
  if (!init.ok()) throw std::runtime_error("hardware plugin '" + plugin_ + "': " + init.message);
  loop_ = std::make_unique<ControlLoop>(config, *hardware_);
  const HardwareResult started = loop_->start(ros::Time::now().toSec());
  if (!started.ok()) throw std::runtime_error("hardware plugin '" + plugin_ + "' did not start: " + started.message);
  loop_->spawn();
  host_ = std::make_unique<LoopHost>(*loop_, setup, joints, [] { return ros::Time::now().toSec(); });
  actions_ = std::make_unique<ControllerActions>(nh_, setup, *host_);

  joint_state_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  diagnostics_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  estop_service_ = pnh_.advertiseService("estop", &DriverNode::estop, this);
  clear_fault_service_ = pnh_.advertiseService("clear_fault", &DriverNode::clearFault, this);
  publish_timer_ =
      nh_.createWallTimer(ros::WallDuration(1.0 / publish_rate), [this](const ros::WallTimerEvent&) { publish(); });
  diagnostics_timer_ =
      nh_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { publishDiagnostics(); });
  std::string names;
  for (const std::string& j : joints) names += (names.empty() ? "" : " ") + j;
  ROS_INFO_STREAM("[sixdof_control] plugin '" << plugin_ << "' on joints " << names << ", " << config.rate
                                              << " Hz, controllers " << controllerSummary(setup));
}

DriverNode::~DriverNode() {
  // Ends every goal while the action servers still exist, then stops the hardware.
  if (loop_) loop_->stop();
}

void DriverNode::publish() {
  const LoopStatus status = loop_->status();
  if (status.state != last_state_) {
    if (status.state == LoopState::kFault) {
      ROS_ERROR_STREAM("[sixdof_control] hardware fault: " << status.fault
                                                           << " (goals are refused until ~clear_fault)");
    } else if (status.state == LoopState::kEstop) {
      ROS_WARN_STREAM("[sixdof_control] e-stop engaged: holding, goals refused until it is released");
    } else {
      ROS_INFO_STREAM("[sixdof_control] " << stateName(status.state));
    }
    last_state_ = status.state;
  }
  const ros::Time stamp(status.time + host_->offset());
  sensor_msgs::JointState js;
  js.header.stamp = stamp;
  for (const PublishedJoint& j : published_) {
    js.name.push_back(j.name);
    js.position.push_back(j.multiplier * status.positions[j.source] + j.offset);
    js.velocity.push_back(j.multiplier * status.velocities[j.source]);
  }
  joint_state_pub_.publish(js);
  actions_->publish(stamp);
}

void DriverNode::publishDiagnostics() {
  const LoopStatus status = loop_->status();
  const PeriodSummary s = loop_->statistics();
  diagnostic_msgs::DiagnosticStatus d;
  d.name = ros::this_node::getName() + ": control loop";
  d.hardware_id = plugin_;
  d.level = status.state == LoopState::kRunning ? diagnostic_msgs::DiagnosticStatus::OK
            : status.state == LoopState::kEstop ? diagnostic_msgs::DiagnosticStatus::WARN
                                                : diagnostic_msgs::DiagnosticStatus::ERROR;
  d.message = status.state == LoopState::kFault ? "fault: " + status.fault : stateName(status.state);
  const auto add = [&d](const std::string& key, double value) {
    diagnostic_msgs::KeyValue kv;
    kv.key = key;
    std::ostringstream text;
    text << value;
    kv.value = text.str();
    d.values.push_back(kv);
  };
  add("rate (Hz)", 1.0 / s.nominal);
  add("periods", static_cast<double>(s.count));
  add("period p50 (ms)", s.period_p50 * 1e3);
  add("period p99 (ms)", s.period_p99 * 1e3);
  add("period error p50 (ms)", s.error_p50 * 1e3);
  add("period error p99 (ms)", s.error_p99 * 1e3);
  add("period error max (ms)", s.error_max * 1e3);
  add("overruns", static_cast<double>(s.overruns));
  add("cycle p50 (ms)", s.cycle_p50 * 1e3);
  add("cycle p99 (ms)", s.cycle_p99 * 1e3);
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(d);
  diagnostics_pub_.publish(array);
}

bool DriverNode::estop(std_srvs::SetBool::Request& request, std_srvs::SetBool::Response& response) {
  loop_->setEstop(request.data);
  response.success = true;
  response.message = request.data ? "e-stop engaged: motion stopped, goals are refused until it is released"
                                  : "e-stop released: holding where the joints are, goals are accepted";
  ROS_WARN_STREAM("[sixdof_control] " << response.message);
  return true;
}

bool DriverNode::clearFault(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  const LoopStatus status = loop_->status();
  if (status.state != LoopState::kFault) {
    response.success = false;
    response.message = std::string("no fault to clear (") + stateName(status.state) + ")";
    return true;
  }
  loop_->clearFault();
  response.success = true;
  response.message = "fault cleared (" + status.fault + "): the next good read holds where the joints are";
  ROS_INFO_STREAM("[sixdof_control] " << response.message);
  return true;
}

}  // namespace sixdof_control
