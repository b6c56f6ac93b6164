// The control loop on the mock plugin (loaded through pluginlib), in simulated time: goals, limits, faults, e-stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <thread>
#include <utility>

#include "sixdof_control/hardware_loader.h"
#include "test_helpers.h"

namespace sixdof_control {
namespace {

using sixdof_core::GoalState;
using sixdof_core::TrajectoryErrorCode;
using test::armGoal;
using test::armLoopConfig;

constexpr double kPeriod = 0.01;

class ControlLoopTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(startWith("{time_constant: 0.02}")); }

  bool startWith(const std::string& params, ControlLoopConfig config = armLoopConfig()) {
    loop.reset();
    hardware = loader.load("mock");
    const HardwareResult init = hardware->init(config.joints, YAML::Load(params));
    EXPECT_TRUE(init.ok()) << init.message;
    loop = std::make_unique<ControlLoop>(config, *hardware);
    now = 0.0;
    const HardwareResult start = loop->start(now);
    EXPECT_TRUE(start.ok()) << start.message;
    return init.ok() && start.ok();
  }

  // Cycles until a goal ends or `seconds` pass; the outcome, if one ended.
  std::optional<GoalOutcome> run(double seconds) {
    outcome.reset();
    const double end = now + seconds;
    while (!outcome && now < end) {
      now += kPeriod;
      loop->cycle(now);
    }
    return outcome;
  }

  void advance(double seconds) {
    for (const double end = now + seconds - 1e-9; now < end;) loop->cycle(now += kPeriod);
  }

  GoalCallback record() {
    return [this](const GoalOutcome& o) { outcome = o; };
  }

  HardwareLoader loader;
  pluginlib::UniquePtr<HardwareInterface> hardware;
  std::unique_ptr<ControlLoop> loop;
  std::optional<GoalOutcome> outcome;
  double now = 0.0;
};

const std::vector<double> kZero(6, 0.0);
const std::vector<double> kTarget = {0.5, -0.3, 0.4, 0.2, 0.3, -0.2};

TEST_F(ControlLoopTest, ExecutesAGoalOnTheMock) {
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {kTarget, 1.0}}), record()).ok());
  ASSERT_TRUE(run(5.0));
  EXPECT_EQ(outcome->state, GoalState::kSucceeded) << outcome->result.message;
  const LoopStatus s = loop->status();
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(s.positions[i], kTarget[i], 0.01);
  const PeriodSummary stats = loop->statistics();
  EXPECT_GT(stats.count, 100u);
  EXPECT_NEAR(stats.period_p50, kPeriod, 1e-9);
}

TEST_F(ControlLoopTest, UnknownPluginIsNamedWithTheDeclaredOnes) {
  try {
    loader.load("warp_drive");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("warp_drive"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sixdof_control/mock"), std::string::npos) << e.what();
  }
}

TEST_F(ControlLoopTest, RefusesAGoalStartingAwayFromTheCurrentState) {
  std::vector<double> away = kZero;
  away[2] = 0.1;
  const auto r = loop->setGoal("arm_controller", armGoal({{away, 0.0}, {kTarget, 1.0}}), record());
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidGoal);
  EXPECT_NE(r.message.find("joint3"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("start_tolerance"), std::string::npos) << r.message;
  // A first point later than 0 is reached from the current state (bridged): accepted.
  EXPECT_TRUE(loop->setGoal("arm_controller", armGoal({{away, 0.5}}), record()).ok());
}

TEST_F(ControlLoopTest, RefusesGoalsBeyondTheLimits) {
  std::vector<double> far = kZero;
  far[0] = 1.0;  // joint1: 1 rad in 0.1 s is 10 rad/s, its limit is 2
  auto r = loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {far, 0.1}}), record());
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidGoal);
  EXPECT_NE(r.message.find("joint1"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("velocity limit"), std::string::npos) << r.message;
  std::vector<double> beyond = kZero;
  beyond[1] = 2.5;  // joint2's URDF limit is 1.92
  r = loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {beyond, 5.0}}), record());
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidGoal);
  EXPECT_NE(r.message.find("outside its limits"), std::string::npos) << r.message;
  EXPECT_EQ(loop->setGoal("elbow_controller", armGoal({{kTarget, 1.0}}), record()).status,
            TrajectoryErrorCode::kInvalidGoal);
}

TEST_F(ControlLoopTest, ACommandBeyondTheVelocityLimitAbortsNamingTheJoint) {
  // 0.19 rad in 0.1 s from rest to rest: 1.9 rad/s on average (under joint1's 2), but the cubic peaks at 2.85.
  std::vector<double> q = kZero;
  q[0] = 0.19;
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {q, 0.1}}), record()).ok());
  ASSERT_TRUE(run(1.0));
  EXPECT_EQ(outcome->state, GoalState::kAborted);
  EXPECT_NE(outcome->result.message.find("joint1"), std::string::npos) << outcome->result.message;
  EXPECT_NE(outcome->result.message.find("exceeds its limit 2"), std::string::npos) << outcome->result.message;
  // The joints hold where they were.
  const std::vector<double> held = loop->status().commands;
  advance(0.2);
  EXPECT_EQ(loop->status().commands, held);
}

TEST_F(ControlLoopTest, ALostDeviceAbortsTheGoalWithinASecondAndRefusesGoals) {
  ASSERT_TRUE(startWith("{time_constant: 0.02, lost_after: 0.3}"));
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {kTarget, 2.0}}), record()).ok());
  ASSERT_TRUE(run(1.3));
  EXPECT_LE(now, 0.3 + 1.0);
  EXPECT_EQ(outcome->state, GoalState::kAborted);
  EXPECT_NE(outcome->result.message.find("disappeared"), std::string::npos) << outcome->result.message;
  EXPECT_EQ(loop->status().state, LoopState::kFault);
  const auto r = loop->setGoal("arm_controller", armGoal({{kTarget, 1.0}}), record());
  EXPECT_NE(r.message.find("hardware fault"), std::string::npos) << r.message;
  // Cleared while the device is still gone, the next read faults again.
  loop->clearFault();
  advance(0.05);
  EXPECT_EQ(loop->status().state, LoopState::kFault);
  // An e-stop engaged during the fault stays engaged when the fault is cleared.
  loop->setEstop(true);
  loop->clearFault();
  EXPECT_EQ(loop->status().state, LoopState::kEstop);
}

// The mock, whose reads fail while `gone`; `during_read` runs inside the next read, as another thread's call would
// while a read is in flight.
class FailingReads : public HardwareInterface {
 public:
  explicit FailingReads(HardwareInterface& mock) : mock_(mock) {}
  HardwareResult init(const std::vector<std::string>& joints, const YAML::Node& params) override {
    return mock_.init(joints, params);
  }
  HardwareResult start() override { return mock_.start(); }
  void stop() override { mock_.stop(); }
  bool hasVelocities() const override { return mock_.hasVelocities(); }
  HardwareResult read(double time, double period, std::vector<double>& positions,
                      std::vector<double>& velocities) override {
    const bool failing = gone;
    if (during_read) std::exchange(during_read, nullptr)();
    if (failing) return HardwareResult::failure(HardwareStatus::kTimeout, "joint3 did not answer");
    return mock_.read(time, period, positions, velocities);
  }
  HardwareResult write(double time, double period, const std::vector<double>& positions) override {
    return mock_.write(time, period, positions);
  }
  bool gone = false;
  std::function<void()> during_read;

 private:
  HardwareInterface& mock_;
};

TEST_F(ControlLoopTest, AReadInFlightWhenTheFaultIsClearedDoesNotFaultAgain) {
  loop.reset();
  FailingReads device(*hardware);
  ControlLoop faulty(armLoopConfig(), device);
  ASSERT_TRUE(faulty.start(now).ok());
  device.gone = true;
  faulty.cycle(now += kPeriod);
  ASSERT_EQ(faulty.status().state, LoopState::kFault);
  // The device comes back and the fault is cleared while a read begun before fails.
  device.during_read = [&] {
    device.gone = false;
    faulty.clearFault();
  };
  faulty.cycle(now += kPeriod);
  EXPECT_EQ(faulty.status().state, LoopState::kRunning) << faulty.status().fault;
  faulty.cycle(now += kPeriod);
  EXPECT_EQ(faulty.status().state, LoopState::kRunning) << faulty.status().fault;
  EXPECT_TRUE(faulty.setGoal("arm_controller", armGoal({{kZero, 0.0}, {kTarget, 1.0}}), record()).ok());
  // A read begun after the clear that fails is a fault again.
  device.gone = true;
  faulty.cycle(now += kPeriod);
  EXPECT_EQ(faulty.status().state, LoopState::kFault);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->state, GoalState::kAborted);
}

TEST_F(ControlLoopTest, AJointThatStopsAnsweringAbortsNamingIt) {
  ASSERT_TRUE(startWith("{unresponsive_joint: joint4, unresponsive_after: 0.2, response_timeout: 0.001}"));
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {kTarget, 2.0}}), record()).ok());
  ASSERT_TRUE(run(1.2));
  EXPECT_EQ(outcome->state, GoalState::kAborted);
  EXPECT_NE(outcome->result.message.find("joint4"), std::string::npos) << outcome->result.message;
  // It holds the positions last read.
  const LoopStatus s = loop->status();
  EXPECT_EQ(s.commands, s.positions);
}

TEST_F(ControlLoopTest, EstopStopsAtOnceAndRefusesGoalsUntilReleased) {
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 0.0}, {kTarget, 2.0}}), record()).ok());
  advance(0.5);
  loop->setEstop(true);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->state, GoalState::kAborted);
  EXPECT_NE(outcome->result.message.find("e-stop"), std::string::npos);
  advance(0.05);
  const std::vector<double> held = loop->status().commands;
  advance(0.5);
  EXPECT_EQ(loop->status().commands, held);
  EXPECT_EQ(loop->status().state, LoopState::kEstop);
  const auto refused = loop->setGoal("arm_controller", armGoal({{kTarget, 1.0}}), record());
  EXPECT_NE(refused.message.find("e-stop engaged"), std::string::npos) << refused.message;
  loop->setEstop(false);
  // A goal right after the release, before the next cycle re-holds where the joints are, runs to its end.
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kTarget, 1.5}}), record()).ok());
  ASSERT_TRUE(run(5.0));
  EXPECT_EQ(outcome->state, GoalState::kSucceeded) << outcome->result.message;
}

TEST_F(ControlLoopTest, APreemptedGoalEndsCanceled) {
  std::optional<GoalOutcome> first;
  ASSERT_TRUE(
      loop->setGoal("arm_controller", armGoal({{kTarget, 2.0}}), [&](const GoalOutcome& o) { first = o; }).ok());
  advance(0.3);
  ASSERT_TRUE(loop->setGoal("arm_controller", armGoal({{kZero, 2.0}}), record()).ok());
  ASSERT_TRUE(first);
  EXPECT_EQ(first->state, GoalState::kCanceled);
  EXPECT_NE(first->result.message.find("preempted"), std::string::npos);
  loop->cancel("arm_controller");
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->state, GoalState::kCanceled);
}

TEST_F(ControlLoopTest, SpawnRunsCyclesOnItsOwnThread) {
  loop->spawn();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (loop->statistics().count < 20 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GE(loop->statistics().count, 20u);
  EXPECT_GT(loop->status().time, 0.0);
  loop->stop();
  EXPECT_EQ(loop->status().state, LoopState::kStopped);
}

TEST_F(ControlLoopTest, GripperGoalsMoveAtTheVelocityLimitAndTheLatestGoalCommands) {
  ASSERT_TRUE(
      startWith("{time_constant: 0.02, initial_positions: {finger1_joint: 0.04}}", test::armAndGripperConfig()));
  std::optional<GripperOutcome> gripper;
  const auto recordGripper = [&](const GripperOutcome& o) { gripper = o; };
  ASSERT_TRUE(loop->setGripperGoal("gripper_controller", {0.01, 0.0}, recordGripper).ok());
  double previous = loop->status().commands[6], fastest = 0.0;
  for (int i = 0; i < 200 && !gripper; ++i) {
    advance(kPeriod);
    fastest = std::max(fastest, std::abs(loop->status().commands[6] - previous) / kPeriod);
    previous = loop->status().commands[6];
  }
  ASSERT_TRUE(gripper);
  EXPECT_EQ(gripper->state, GoalState::kSucceeded) << gripper->message;
  EXPECT_TRUE(gripper->reached_goal);
  EXPECT_NEAR(fastest, 0.1, 1e-9);  // finger1_joint's velocity limit (joint_limits.yaml)

  // The finger's trajectory controller takes the joint back, preempting a new gripper goal, and the other way round.
  gripper.reset();
  ASSERT_TRUE(loop->setGripperGoal("gripper_controller", {0.04, 0.0}, recordGripper).ok());
  advance(0.05);
  sixdof_core::TrajectoryGoal fingers;
  fingers.joint_names = {"finger1_joint"};
  fingers.points = {{{0.03}, {0.0}, {}, 1.0}};
  ASSERT_TRUE(loop->setGoal("gripper_controller", fingers, record()).ok());
  ASSERT_TRUE(gripper);
  EXPECT_EQ(gripper->state, GoalState::kCanceled);
  EXPECT_NE(gripper->message.find("preempted by controller 'gripper_controller'"), std::string::npos);
  advance(0.05);
  outcome.reset();
  ASSERT_TRUE(loop->setGripperGoal("gripper_controller", {0.02, 0.0}, recordGripper).ok());
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->state, GoalState::kCanceled);
  EXPECT_NE(outcome->result.message.find("preempted by gripper"), std::string::npos);

  loop->setEstop(true);
  const auto refused = loop->setGripperGoal("gripper_controller", {0.02, 0.0}, recordGripper);
  EXPECT_EQ(refused.status, sixdof_core::GripperStatus::kRefused);
  EXPECT_NE(refused.message.find("e-stop"), std::string::npos) << refused.message;
  EXPECT_EQ(loop->setGripperGoal("suction_cup", {0.02, 0.0}, recordGripper).status,
            sixdof_core::GripperStatus::kRefused);
}

TEST(ControlLoopConfig, BadConfigsAreNamed) {
  HardwareLoader loader;
  auto hardware = loader.load("mock");
  ControlLoopConfig c = armLoopConfig();
  c.controllers[0].joints[5] = "wrist";
  try {
    ControlLoop loop(c, *hardware);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'wrist'"), std::string::npos) << e.what();
  }
  c = armLoopConfig();
  c.controllers.push_back(c.controllers[0]);
  c.controllers[1].name = "second";
  EXPECT_THROW(ControlLoop(c, *hardware), std::invalid_argument);
  c = armLoopConfig();
  c.rate = 0.0;
  EXPECT_THROW(ControlLoop(c, *hardware), std::invalid_argument);
  c = armLoopConfig();
  c.realtime_priority = 100;
  EXPECT_THROW(ControlLoop(c, *hardware), std::invalid_argument);
}

TEST(MockHardware, RefusesUnknownAndBadParameters) {
  HardwareLoader loader;
  auto hardware = loader.load("mock");
  HardwareResult r = hardware->init({"a"}, YAML::Load("{time_constnt: 0.1}"));
  EXPECT_EQ(r.status, HardwareStatus::kInvalidConfig);
  EXPECT_NE(r.message.find("time_constnt"), std::string::npos) << r.message;
  r = hardware->init({"a"}, YAML::Load("{time_constant: -1}"));
  EXPECT_NE(r.message.find("time_constant"), std::string::npos) << r.message;
  r = hardware->init({"a"}, YAML::Load("{unresponsive_joint: b}"));
  EXPECT_NE(r.message.find("'b'"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace sixdof_control
