// The dynamixel plugin (loaded through pluginlib) driving the Protocol 2.0 emulator on a pseudo-terminal.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "emulator_process.h"
#include "sixdof_control/hardware_loader.h"
#include "test_helpers.h"

namespace sixdof_control {
namespace {

using test::EmulatorProcess;

const std::vector<std::string> kJoints = {"joint1", "joint2", "joint3"};

std::string params(const std::string& port, int third_id = 3) {
  return "{port: " + port +
         ", baud: 1000000, timeout: 0.05, joints: {joint1: {id: 1}, "
         "joint2: {id: 2, direction: -1, zero_offset: 0.5}, joint3: {id: " +
         std::to_string(third_id) + ", gear_ratio: 2}}}";
}

class DynamixelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hardware = loader.load("dynamixel");
    const HardwareResult r = hardware->init(kJoints, YAML::Load(params(emulator.port())));
    ASSERT_TRUE(r.ok()) << r.message;
  }

  HardwareResult read() { return hardware->read(0.0, 0.01, positions, velocities); }
  // Starts the hardware, then has the emulator inject `fault` (one of its commands).
  void startThenInject(const std::string& fault) {
    ASSERT_TRUE(hardware->start().ok());
    ASSERT_EQ(emulator.send(fault), "ok");
  }

  EmulatorProcess emulator{{"--ids", "1", "2", "3"}};
  HardwareLoader loader;
  pluginlib::UniquePtr<HardwareInterface> hardware;
  std::vector<double> positions = std::vector<double>(3, 0.0);
  std::vector<double> velocities = std::vector<double>(3, 0.0);
};

TEST_F(DynamixelTest, MovesReadsBackAndSwitchesTorque) {
  for (const char* id : {"1", "2", "3"}) EXPECT_EQ(emulator.send(std::string("get ") + id + " 64 1"), "0");
  ASSERT_TRUE(hardware->start().ok());
  for (const char* id : {"1", "2", "3"}) EXPECT_EQ(emulator.send(std::string("get ") + id + " 64 1"), "1");
  ASSERT_TRUE(read().ok());
  // Every servo at its centre: joint2 is direction -1 with zero offset 0.5 rad.
  EXPECT_NEAR(positions[0], 0.0, 1e-12);
  EXPECT_NEAR(positions[1], 0.5, 1e-12);
  EXPECT_NEAR(positions[2], 0.0, 1e-12);

  ASSERT_TRUE(hardware->write(0.0, 0.01, {0.3, 0.2, 0.1}).ok());
  // No status packet answers a sync write: the next read's replies show the servos have it.
  ASSERT_TRUE(read().ok());
  ASSERT_TRUE(read().ok());
  const double pulses_per_rad = 4096.0 / (2.0 * M_PI);
  EXPECT_EQ(emulator.send("get 1 116 4"), std::to_string(std::lround(2048 + 0.3 * pulses_per_rad)));
  EXPECT_EQ(emulator.send("get 2 116 4"), std::to_string(std::lround(2048 + (-0.2 + 0.5) * pulses_per_rad)));
  EXPECT_EQ(emulator.send("get 3 116 4"), std::to_string(std::lround(2048 + 0.1 * 2.0 * pulses_per_rad)));
  const double pulse = 1.0 / pulses_per_rad;
  EXPECT_NEAR(positions[0], 0.3, pulse);
  EXPECT_NEAR(positions[1], 0.2, pulse);
  EXPECT_NEAR(positions[2], 0.1, pulse / 2.0);

  hardware->stop();
  for (const char* id : {"1", "2", "3"}) EXPECT_EQ(emulator.send(std::string("get ") + id + " 64 1"), "0");
}

TEST_F(DynamixelTest, StartHoldsWhereTheServosAre) {
  emulator.send("set 3 132 4 2500");
  ASSERT_TRUE(hardware->start().ok());
  EXPECT_EQ(emulator.send("get 3 116 4"), "2500");
}

TEST_F(DynamixelTest, HardwareErrorIsReportedNamingTheJoint) {
  ASSERT_NO_FATAL_FAILURE(startThenInject("hardware_error 2 32"));
  const HardwareResult r = read();
  EXPECT_EQ(r.status, HardwareStatus::kDeviceError);
  EXPECT_NE(r.message.find("joint 'joint2' (id 2)"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("overload"), std::string::npos) << r.message;
}

TEST_F(DynamixelTest, AServoThatStopsAnsweringTimesOutNamingTheJoint) {
  ASSERT_NO_FATAL_FAILURE(startThenInject("remove 3"));
  const HardwareResult r = read();
  EXPECT_EQ(r.status, HardwareStatus::kTimeout);
  EXPECT_NE(r.message.find("joint 'joint3'"), std::string::npos) << r.message;
}

TEST_F(DynamixelTest, APortThatVanishesIsLost) {
  ASSERT_NO_FATAL_FAILURE(startThenInject("vanish"));
  HardwareResult r = read();
  if (r.ok()) r = hardware->write(0.0, 0.01, {0.0, 0.5, 0.0});
  EXPECT_EQ(r.status, HardwareStatus::kDeviceLost) << r.message;
}

TEST(DynamixelConfig, MissingServosAndBadParametersAreNamed) {
  EmulatorProcess emulator({"--ids", "1", "2", "3"});
  HardwareLoader loader;
  auto hardware = loader.load("dynamixel");
  HardwareResult r = hardware->init(kJoints, YAML::Load(params(emulator.port(), 7)));
  EXPECT_EQ(r.status, HardwareStatus::kDeviceNotFound);
  EXPECT_NE(r.message.find("joint 'joint3' (id 7"), std::string::npos) << r.message;
  r = hardware->init(kJoints, YAML::Load("{baud: 57600}"));
  EXPECT_EQ(r.status, HardwareStatus::kInvalidConfig);
  EXPECT_NE(r.message.find("port"), std::string::npos) << r.message;
  r = hardware->init(kJoints, YAML::Load("{port: /dev/null, joints: {joint1: {id: 1, gear: 2}}}"));
  EXPECT_NE(r.message.find("gear"), std::string::npos) << r.message;
  r = hardware->init(kJoints, YAML::Load("{port: /nonexistent/tty, joints: {joint1: {id: 1}, joint2: {id: 2}, "
                                         "joint3: {id: 3}}}"));
  EXPECT_EQ(r.status, HardwareStatus::kDeviceNotFound);
  EXPECT_NE(r.message.find("/nonexistent/tty"), std::string::npos) << r.message;
}

// The control loop on its own thread at 100 Hz with servos that lag: a goal succeeds; a servo that disappears
// mid-motion aborts the next goal within a second, naming its joint.
TEST(DynamixelControlLoop, RunsGoalsAndAbortsWhenAServoDisappears) {
  EmulatorProcess emulator({"--ids", "1", "2", "3", "--lag", "0.03"});
  HardwareLoader loader;
  auto hardware = loader.load("dynamixel");
  ASSERT_TRUE(hardware->init(kJoints, YAML::Load(params(emulator.port()))).ok());
  ControlLoopConfig config = test::armLoopConfig();
  config.joints = kJoints;
  config.limits.resize(3);
  config.controllers[0].joints = kJoints;
  config.controllers[0].path_tolerance.resize(3);
  config.controllers[0].goal_tolerance.resize(3);
  ControlLoop loop(config, *hardware);
  ASSERT_TRUE(loop.start(0.0).ok());
  loop.spawn();

  std::mutex mutex;
  std::condition_variable changed;
  std::optional<GoalOutcome> outcome;
  const auto record = [&](const GoalOutcome& o) {
    std::lock_guard<std::mutex> lock(mutex);
    outcome = o;
    changed.notify_all();
  };
  const auto wait = [&](double seconds) {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return outcome.has_value(); });
    return outcome;
  };
  sixdof_core::TrajectoryGoal goal;
  goal.joint_names = kJoints;
  goal.points = {{{0.3, 0.2, -0.2}, {0.0, 0.0, 0.0}, {}, 1.0}};
  ASSERT_TRUE(loop.setGoal("arm_controller", goal, record).ok());
  ASSERT_TRUE(wait(5.0));
  EXPECT_EQ(outcome->state, sixdof_core::GoalState::kSucceeded) << outcome->result.message;
  const PeriodSummary stats = loop.statistics();
  std::printf(
      "dynamixel on the emulator, 3 servos at 100 Hz: cycle (sync read + sync write) p50 %.2f ms, p99 %.2f "
      "ms; period error p50 %.3f ms, p99 %.3f ms over %zu periods\n",
      stats.cycle_p50 * 1e3, stats.cycle_p99 * 1e3, stats.error_p50 * 1e3, stats.error_p99 * 1e3, stats.count);

  outcome.reset();
  goal.points = {{{-0.3, 0.6, 0.2}, {0.0, 0.0, 0.0}, {}, 2.0}};
  ASSERT_TRUE(loop.setGoal("arm_controller", goal, record).ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto removed = std::chrono::steady_clock::now();
  ASSERT_EQ(emulator.send("remove 2"), "ok");
  ASSERT_TRUE(wait(1.0)) << "no abort within 1 s";
  EXPECT_LE(std::chrono::duration<double>(std::chrono::steady_clock::now() - removed).count(), 1.0);
  EXPECT_EQ(outcome->state, sixdof_core::GoalState::kAborted);
  EXPECT_NE(outcome->result.message.find("joint 'joint2'"), std::string::npos) << outcome->result.message;
  loop.stop();
}

}  // namespace
}  // namespace sixdof_control
