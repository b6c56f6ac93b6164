#pragma once
// The hardware interface of sixdof_control: what a plugin implements so that the control loop (control_loop.h) runs
// the trajectory and gripper controllers on a device. ros_control's RobotHW in miniature, without ROS types:
// positions in, position commands out, errors as results.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "sixdof_core/result.h"

namespace sixdof_control {

enum class HardwareStatus {
  kOk = 0,
  kInvalidConfig,       // init: a parameter is missing, of the wrong type or out of range (the message names it)
  kDeviceNotFound,      // init/start: the port cannot be opened, or a device does not answer
  kTimeout,             // a device did not answer within the plugin's timeout
  kDeviceLost,          // the device went away (port closed, cable pulled)
  kDeviceError,         // a device reports an error (a servo's hardware error status: overload, overheating, ...)
  kCommunicationError,  // a corrupt or unexpected reply (checksum, framing, wrong id)
};

// Every failure's message names the joint or device and the problem, e.g. "joint 'joint3' (id 3): no status
// packet within 20 ms".
using HardwareResult = sixdof_core::Result<HardwareStatus>;

// A device that moves some joints. Plugins derive from it, have a default constructor, and are exported with
// PLUGINLIB_EXPORT_CLASS(MyHardware, sixdof_control::HardwareInterface) (docs/real_robot.md, "Writing a plugin").
//
// The control loop calls init() once, start() once, then read() and write() alternately at its rate from one thread,
// and stop() at the end. Units are the joints' own (rad for revolute joints, m for prismatic ones) in the
// robot's joint frames: calibration (zero offsets, directions, gear ratios) happens inside the plugin.
class HardwareInterface {
 public:
  virtual ~HardwareInterface() = default;

  // Reads the plugin's parameters (its block of hardware.yaml) for these joints, in this order (every later
  // vector is in it), and connects to the device. Must not move anything. A bad parameter gives kInvalidConfig
  // naming it; an unknown parameter is an error too, not ignored.
  virtual HardwareResult init(const std::vector<std::string>& joints, const YAML::Node& params) = 0;

  // Makes the device ready to move (e.g. torque on) without moving it: until the first write() it holds where it
  // is.
  virtual HardwareResult start() = 0;

  // Makes the device safe (e.g. torque off) and disconnects. Called once after start(), also after a failure;
  // must not throw.
  virtual void stop() = 0;

  // Whether read() measures velocities. Without, the control loop differentiates the positions.
  virtual bool hasVelocities() const = 0;

  // The joints' positions (and velocities when hasVelocities()) now. `time` is the loop's clock (s), `period` the
  // time since the previous read. Must return within the plugin's timeout (a few periods of the loop at most): a
  // device that does not answer is kTimeout, not a wait. The vectors are sized by the caller.
  virtual HardwareResult read(double time, double period, std::vector<double>& positions,
                              std::vector<double>& velocities) = 0;

  // Commands the joints' positions. The control loop has checked them against the joint limits.
  virtual HardwareResult write(double time, double period, const std::vector<double>& positions) = 0;
};

}  // namespace sixdof_control
