#include "dynamixel_hardware.h"

#include <algorithm>
#include <cmath>
#include <pluginlib/class_list_macros.hpp>
#include <set>
#include <sstream>

namespace sixdof_control {

using dynamixel::Bytes;
namespace address = dynamixel::address;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerPulse = 2.0 * kPi / dynamixel::kPulsesPerRevolution;
constexpr double kRadPerSecondPerUnit = dynamixel::kVelocityUnitRpm * 2.0 * kPi / 60.0;

HardwareResult invalid(const std::string& why) {
  return HardwareResult::failure(HardwareStatus::kInvalidConfig, "dynamixel: " + why);
}

template <class T>
bool get(const YAML::Node& node, T& value) {
  try {
    value = node.as<T>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

}  // namespace

DynamixelHardware::~DynamixelHardware() { stop(); }

HardwareResult DynamixelHardware::named(HardwareResult r, int failed_id) const {
  if (r.ok()) return r;
  for (const Servo& s : servos_) {
    if (s.id == failed_id) {
      r.message = "joint '" + s.joint + "' (" + r.message + ")";
      return r;
    }
  }
  r.message = "dynamixel bus " + port_ + ": " + r.message;
  return r;
}

HardwareResult DynamixelHardware::init(const std::vector<std::string>& joints, const YAML::Node& params) {
  static const std::set<std::string> kKeys = {"port", "baud", "timeout", "joints"};
  static const std::set<std::string> kJointKeys = {"id", "zero_offset", "direction", "gear_ratio"};
  if (!params || !params.IsMap()) return invalid("parameters port, baud, timeout and joints are needed");
  for (const auto& kv : params) {
    if (kKeys.count(kv.first.as<std::string>()) == 0)
      return invalid("unknown parameter '" + kv.first.as<std::string>() + "'");
  }
  if (!params["port"] || !get(params["port"], port_) || port_.empty())
    return invalid("port (a device path) is required");
  int baud = 57600;
  if (params["baud"] && !get(params["baud"], baud)) return invalid("baud must be an integer");
  double timeout = 0.02;
  if (params["timeout"] && (!get(params["timeout"], timeout) || !(timeout > 0.0) || !std::isfinite(timeout))) {
    return invalid("timeout must be a number > 0 (s)");
  }
  const YAML::Node table = params["joints"];
  if (!table || !table.IsMap())
    return invalid("joints must map every joint to {id, zero_offset, direction, gear_ratio}");
  for (const auto& kv : table) {
    const std::string name = kv.first.as<std::string>();
    if (std::find(joints.begin(), joints.end(), name) == joints.end()) {
      return invalid("joints names '" + name + "', which is not one of the hardware's joints");
    }
  }
  servos_.clear();
  std::set<int> ids;
  for (const std::string& joint : joints) {
    const YAML::Node j = table[joint];
    const std::string at = "joints/" + joint + "/";
    if (!j || !j.IsMap()) return invalid("joint '" + joint + "' has no entry under joints (id is required)");
    for (const auto& kv : j) {
      if (kJointKeys.count(kv.first.as<std::string>()) == 0)
        return invalid("unknown key '" + at + kv.first.as<std::string>() + "'");
    }
    Servo s;
    s.joint = joint;
    int id = -1;
    if (!j["id"] || !get(j["id"], id) || id < 0 || id > 252) return invalid(at + "id must be an integer in 0..252");
    if (!ids.insert(id).second) return invalid(at + "id " + std::to_string(id) + " is used by another joint");
    s.id = static_cast<std::uint8_t>(id);
    if (j["zero_offset"] && (!get(j["zero_offset"], s.zero_offset) || !std::isfinite(s.zero_offset))) {
      return invalid(at + "zero_offset must be a number (rad)");
    }
    if (j["direction"] && (!get(j["direction"], s.direction) || (s.direction != 1.0 && s.direction != -1.0))) {
      return invalid(at + "direction must be 1 or -1");
    }
    if (j["gear_ratio"] &&
        (!get(j["gear_ratio"], s.gear_ratio) || !(s.gear_ratio > 0.0) || !std::isfinite(s.gear_ratio))) {
      return invalid(at + "gear_ratio must be a number > 0");
    }
    servos_.push_back(s);
  }
  ids_.clear();
  for (const Servo& s : servos_) ids_.push_back(s.id);
  const std::string why = bus_.open(port_, baud, timeout);
  if (!why.empty()) return HardwareResult::failure(HardwareStatus::kDeviceNotFound, "dynamixel: " + why);
  open_ = true;
  for (const Servo& s : servos_) {
    int failed = -1;
    HardwareResult r = bus_.ping(s.id, failed);
    if (!r.ok()) {
      r.message += " (ping on " + port_ + " at " + std::to_string(baud) + " baud)";
      return named(r, failed);
    }
  }
  return {};
}

HardwareResult DynamixelHardware::setTorque(bool on) {
  for (const Servo& s : servos_) {
    int failed = -1;
    const HardwareResult r = bus_.write(s.id, address::kTorqueEnable, Bytes{static_cast<std::uint8_t>(on)}, failed);
    if (!r.ok()) return named(r, failed);
  }
  torque_ = on;
  return {};
}

HardwareResult DynamixelHardware::start() {
  if (!open_) return invalid("start before a successful init");
  // The goal positions become the present ones before the torque goes on: nothing moves.
  std::vector<Bytes> data;
  std::vector<std::uint8_t> errors;
  int failed = -1;
  HardwareResult r = bus_.syncRead(address::kPresentPosition, 4, ids_, data, errors, failed);
  if (!r.ok()) return named(r, failed);
  std::vector<std::pair<std::uint8_t, Bytes>> goals;
  for (std::size_t i = 0; i < ids_.size(); ++i) goals.emplace_back(ids_[i], data[i]);
  r = bus_.syncWrite(address::kGoalPosition, 4, goals, failed);
  if (!r.ok()) return named(r, failed);
  return setTorque(true);
}

void DynamixelHardware::stop() {
  if (!open_) return;
  if (torque_) setTorque(false);
  bus_.close();
  open_ = false;
}

HardwareResult DynamixelHardware::read(double, double, std::vector<double>& positions,
                                       std::vector<double>& velocities) {
  std::vector<Bytes> data;
  std::vector<std::uint8_t> errors;
  int failed = -1;
  const HardwareResult r = bus_.syncRead(address::kPresentVelocity, 8, ids_, data, errors, failed);
  if (!r.ok()) return named(r, failed);
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    const Servo& s = servos_[i];
    if (errors[i] & dynamixel::kAlertBit) {
      Bytes status;
      const HardwareResult e = bus_.read(s.id, address::kHardwareErrorStatus, 1, status, failed);
      if (!e.ok()) return named(e, failed);
      std::ostringstream m;
      m << "joint '" << s.joint << "' (id " << int(s.id) << "): hardware error status 0x" << std::hex << int(status[0])
        << std::dec << " (" << dynamixel::hardwareErrorNames(status[0]) << ")";
      return HardwareResult::failure(HardwareStatus::kDeviceError, m.str());
    }
    const double angle = (dynamixel::readI32(data[i], 4) - dynamixel::kCentrePulse) * kRadPerPulse;
    positions[i] = s.direction * (angle - s.zero_offset) / s.gear_ratio;
    velocities[i] = s.direction * dynamixel::readI32(data[i], 0) * kRadPerSecondPerUnit / s.gear_ratio;
  }
  return {};
}

HardwareResult DynamixelHardware::write(double, double, const std::vector<double>& positions) {
  std::vector<std::pair<std::uint8_t, Bytes>> goals;
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    const Servo& s = servos_[i];
    const double angle = s.direction * positions[i] * s.gear_ratio + s.zero_offset;
    const double pulse = std::round(angle / kRadPerPulse + dynamixel::kCentrePulse);
    if (!(pulse >= 0.0 && pulse < dynamixel::kPulsesPerRevolution)) {
      std::ostringstream m;
      m << "joint '" << s.joint << "' (id " << int(s.id) << "): command " << positions[i] << " is goal position "
        << pulse << ", outside the servo's range 0..4095 (check zero_offset, direction and gear_ratio)";
      return HardwareResult::failure(HardwareStatus::kInvalidConfig, m.str());
    }
    Bytes bytes;
    dynamixel::appendI32(bytes, static_cast<std::int32_t>(pulse));
    goals.emplace_back(s.id, bytes);
  }
  int failed = -1;
  return named(bus_.syncWrite(address::kGoalPosition, 4, goals, failed), failed);
}

}  // namespace sixdof_control

PLUGINLIB_EXPORT_CLASS(sixdof_control::DynamixelHardware, sixdof_control::HardwareInterface)
