#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus.h"
#include "sixdof_control/hardware_interface.h"

namespace sixdof_control {

// `dynamixel`: X series servos (position control mode, one turn: pulses 0..4095) on one Protocol 2.0 bus.
// Parameters (hardware.yaml):
//   port: the serial device, e.g. /dev/ttyUSB0 (required)
//   baud: 9600, 57600 (default), 115200, 1000000, 2000000, 3000000 or 4000000
//   timeout: s, > 0 (0.02): how long a reply is awaited
//   joints: {<joint>: {id, zero_offset, direction, gear_ratio}} for every joint of the robot's hardware:
//     id: 0..252 (required); zero_offset: the servo's angle (rad from its centre, pulse 2048) when the joint is at
//     zero (0); direction: 1 or -1, the sign of the joint's motion for the servo's positive one (1); gear_ratio:
//     servo radians per joint unit (rad or m), > 0 (1)
// The joint position is direction * (servo angle - zero_offset) / gear_ratio.
// init pings every servo; start writes each servo's goal position to its present one, then torque on; stop turns
// torque off. read is one sync read of present velocity and position (addresses 128..135); a status packet with the
// alert bit makes it read that servo's Hardware Error Status (70) and fail with kDeviceError naming the joint, id
// and error. write is one sync write of goal positions (116).
class DynamixelHardware : public HardwareInterface {
 public:
  ~DynamixelHardware() override;
  HardwareResult init(const std::vector<std::string>& joints, const YAML::Node& params) override;
  HardwareResult start() override;
  void stop() override;
  bool hasVelocities() const override { return true; }
  HardwareResult read(double time, double period, std::vector<double>& positions,
                      std::vector<double>& velocities) override;
  HardwareResult write(double time, double period, const std::vector<double>& positions) override;

 private:
  struct Servo {
    std::string joint;
    std::uint8_t id = 1;
    double zero_offset = 0.0;
    double direction = 1.0;
    double gear_ratio = 1.0;
  };
  // The result with the joint and id named in front of the bus's message.
  HardwareResult named(HardwareResult r, int failed_id) const;
  HardwareResult setTorque(bool on);

  std::vector<Servo> servos_;
  std::vector<std::uint8_t> ids_;
  dynamixel::Bus bus_;
  std::string port_;
  bool open_ = false;
  bool torque_ = false;
};

}  // namespace sixdof_control
