#include "mock_hardware.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <pluginlib/class_list_macros.hpp>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

namespace sixdof_control {
namespace {

HardwareResult invalid(const std::string& why) {
  return HardwareResult::failure(HardwareStatus::kInvalidConfig, "mock: " + why);
}

// Reads a number >= minimum into `value` when the key is present.
HardwareResult number(const YAML::Node& params, const std::string& key, double minimum, double& value) {
  if (!params[key]) return {};
  try {
    value = params[key].as<double>();
  } catch (const YAML::Exception&) {
    return invalid(key + " must be a number");
  }
  if (!std::isfinite(value) || value < minimum) {
    std::ostringstream s;
    s << key << " must be finite and >= " << minimum << " (got " << value << ")";
    return invalid(s.str());
  }
  return {};
}

}  // namespace

HardwareResult MockHardware::init(const std::vector<std::string>& joints, const YAML::Node& params) {
  static const std::set<std::string> kKeys = {"time_constant",      "position_noise",   "seed",
                                              "initial_positions",  "response_timeout", "unresponsive_joint",
                                              "unresponsive_after", "lost_after",       "fault_clock"};
  joints_ = joints;
  const std::size_t n = joints.size();
  q_.assign(n, 0.0);
  v_.assign(n, 0.0);
  if (params && !params.IsNull()) {
    if (!params.IsMap()) return invalid("the parameters must be a mapping");
    for (const auto& kv : params) {
      if (kKeys.count(kv.first.as<std::string>()) == 0)
        return invalid("unknown parameter '" + kv.first.as<std::string>() + "'");
    }
    HardwareResult r;
    for (auto [key, minimum, value] :
         {std::make_tuple("time_constant", 0.0, &time_constant_), std::make_tuple("position_noise", 0.0, &noise_),
          std::make_tuple("response_timeout", 1e-6, &response_timeout_),
          std::make_tuple("unresponsive_after", 0.0, &unresponsive_after_),
          std::make_tuple("lost_after", 0.0, &lost_after_)}) {
      if (!(r = number(params, key, minimum, *value)).ok()) return r;
    }
    double seed = 0.0;
    if (!(r = number(params, "seed", 0.0, seed)).ok()) return r;
    rng_.seed(static_cast<unsigned>(seed));
    if (const YAML::Node clock = params["fault_clock"]) {
      const std::string value = clock.as<std::string>();
      if (value != "first_read" && value != "first_motion") {
        return invalid("fault_clock must be first_read or first_motion, got '" + value + "'");
      }
      faults_from_motion_ = value == "first_motion";
    }
    if (params["unresponsive_joint"]) {
      const std::string name = params["unresponsive_joint"].as<std::string>();
      const auto it = std::find(joints_.begin(), joints_.end(), name);
      if (it == joints_.end()) return invalid("unresponsive_joint '" + name + "' is not one of the joints");
      unresponsive_ = static_cast<int>(it - joints_.begin());
    }
    if (const YAML::Node initial = params["initial_positions"]) {
      if (!initial.IsMap()) return invalid("initial_positions must map joints to positions");
      for (const auto& kv : initial) {
        const std::string name = kv.first.as<std::string>();
        const auto it = std::find(joints_.begin(), joints_.end(), name);
        if (it == joints_.end()) return invalid("initial_positions names '" + name + "', not one of the joints");
        double value = 0.0;
        if (!(r = number(initial, name, -1e9, value)).ok()) return r;
        q_[static_cast<std::size_t>(it - joints_.begin())] = value;
      }
    }
  }
  command_ = q_;
  initial_ = q_;
  return {};
}

HardwareResult MockHardware::start() {
  started_ = true;
  return {};
}

void MockHardware::stop() { started_ = false; }

HardwareResult MockHardware::lost(double time) const {
  if (lost_after_ >= 0.0 && fault_clock_started_ && time - fault_origin_ >= lost_after_) {
    std::string joints;
    for (const std::string& j : joints_) joints += (joints.empty() ? "" : ", ") + j;
    return HardwareResult::failure(HardwareStatus::kDeviceLost,
                                   "mock: the device of joints " + joints + " disappeared");
  }
  return {};
}

HardwareResult MockHardware::read(double time, double period, std::vector<double>& positions,
                                  std::vector<double>& velocities) {
  if (!fault_clock_started_ && !faults_from_motion_) {
    fault_clock_started_ = true;
    fault_origin_ = time;
  }
  if (HardwareResult r = lost(time); !r.ok()) return r;
  if (unresponsive_ >= 0 && fault_clock_started_ && time - fault_origin_ >= unresponsive_after_) {
    std::this_thread::sleep_for(std::chrono::duration<double>(response_timeout_));
    std::ostringstream s;
    s << "mock: joint '" << joints_[static_cast<std::size_t>(unresponsive_)] << "' did not answer within "
      << response_timeout_ << " s";
    return HardwareResult::failure(HardwareStatus::kTimeout, s.str());
  }
  // First-order lag over the period: exact for a command held constant since the previous write.
  const double alpha = time_constant_ > 0.0 ? 1.0 - std::exp(-std::max(period, 0.0) / time_constant_) : 1.0;
  std::normal_distribution<double> noise(0.0, noise_);
  for (std::size_t i = 0; i < q_.size(); ++i) {
    const double before = q_[i];
    q_[i] += alpha * (command_[i] - q_[i]);
    v_[i] = period > 0.0 ? (q_[i] - before) / period : 0.0;
    positions[i] = q_[i] + (noise_ > 0.0 ? noise(rng_) : 0.0);
    velocities[i] = v_[i];
  }
  return {};
}

HardwareResult MockHardware::write(double time, double, const std::vector<double>& positions) {
  if (HardwareResult r = lost(time); !r.ok()) return r;
  if (!started_) return {};
  command_ = positions;
  if (!fault_clock_started_) {
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (std::abs(positions[i] - initial_[i]) > 1e-6) {
        fault_clock_started_ = true;
        fault_origin_ = time;
        break;
      }
    }
  }
  return {};
}

}  // namespace sixdof_control

PLUGINLIB_EXPORT_CLASS(sixdof_control::MockHardware, sixdof_control::HardwareInterface)
