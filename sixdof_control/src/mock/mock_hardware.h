#pragma once

#include <random>
#include <string>
#include <vector>

#include "sixdof_control/hardware_interface.h"

namespace sixdof_control {

// `mock`: joints that follow their commands with a first-order lag, for tests, the benchmark and trying the
// driver without a robot. Parameters (all optional):
//   time_constant: s, > 0 (0.05): each joint moves as q' = (command - q) / time_constant; 0 follows at once
//   position_noise: m or rad, >= 0 (0): standard deviation of Gaussian noise on each reading
//   seed: integer (0): of the noise
//   initial_positions: {<joint>: value} (0 for joints not named)
//   response_timeout: s, > 0 (0.02): how long a read waits for an unresponsive joint
//   unresponsive_joint, unresponsive_after: that joint stops answering that many seconds after the fault clock's
//     start (reads then fail with kTimeout naming it)
//   lost_after: s: the device disappears that many seconds after the fault clock's start (reads and writes fail
//     with kDeviceLost naming its joints)
//   fault_clock: first_read (default): the faults' seconds count from the first read; first_motion: from the first
//     command away from the initial positions (a fault in the middle of the first motion, whenever it comes)
class MockHardware : public HardwareInterface {
 public:
  HardwareResult init(const std::vector<std::string>& joints, const YAML::Node& params) override;
  HardwareResult start() override;
  void stop() override;
  bool hasVelocities() const override { return true; }
  HardwareResult read(double time, double period, std::vector<double>& positions,
                      std::vector<double>& velocities) override;
  HardwareResult write(double time, double period, const std::vector<double>& positions) override;

 private:
  HardwareResult lost(double time) const;

  std::vector<std::string> joints_;
  std::vector<double> q_, v_, command_;
  double time_constant_ = 0.05;
  double noise_ = 0.0;
  double response_timeout_ = 0.02;
  int unresponsive_ = -1;  // joint index
  double unresponsive_after_ = 0.0;
  double lost_after_ = -1.0;  // < 0: never
  std::vector<double> initial_;
  bool started_ = false;
  bool faults_from_motion_ = false;
  bool fault_clock_started_ = false;
  double fault_origin_ = 0.0;
  std::mt19937 rng_;
};

}  // namespace sixdof_control
