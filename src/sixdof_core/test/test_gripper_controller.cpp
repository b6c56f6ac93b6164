#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sixdof_core/control/gripper_controller.h"

namespace sixdof_core {
namespace {

constexpr double kDt = 0.001;

GripperControllerConfig fingerConfig(bool allow_stalling) {
  GripperControllerConfig c;
  c.name = "gripper_controller";
  c.joint = "finger1_joint";
  c.lower = 0.0;
  c.upper = 0.04;
  c.effort_limit = 20.0;
  c.goal_tolerance = 0.001;
  c.stall_velocity_threshold = 0.001;
  c.stall_timeout = 0.2;
  c.allow_stalling = allow_stalling;
  return c;
}

constexpr double kRockPeriod = 0.1;  // s

// A finger servoing towards the command at a bounded speed, blocked below `obstacle` (an object between
// the fingers). Pressed against the obstacle it jitters by `jitter` each step (a contact in physics), rocks
// back and forth up to `rock` away from it (a linkage pressed on a round object), and the obstacle gives way
// towards the target at `creep` speed.
struct Finger {
  double q = 0.04;
  double obstacle = -1.0;
  double speed = 0.05;
  double jitter = 0.0;
  double rock = 0.0;
  double creep = 0.0;
  bool pressed = false;
  int steps = 0;
  void apply(const GripperUpdate& u) {
    const double step = std::clamp(u.command_position - q, -speed * kDt, speed * kDt);
    q = std::max(q + step, obstacle);
    pressed = u.command_position < obstacle && (pressed || q == obstacle);
    if (pressed) {
      ++steps;
      obstacle -= creep * kDt;
      q = obstacle + (steps % 2 ? jitter : 0.0) + rock * 0.5 * (1.0 - std::cos(2.0 * M_PI * steps * kDt / kRockPeriod));
    }
  }
};

GripperUpdate run(GripperController& c, Finger& f, double& now, double max_time) {
  GripperUpdate u;
  const double end = now + max_time;
  while (now < end) {
    u = c.update(now, f.q);
    f.apply(u);
    now += kDt;
    if (u.finished) {
      break;
    }
  }
  return u;
}

// A controller and its finger from time 0.
struct Rig {
  explicit Rig(bool allow_stalling) : c(fingerConfig(allow_stalling)) {}

  // Sends `goal` now and steps until it finishes or 5 s have passed: the last update.
  GripperUpdate runGoal(const GripperGoal& goal) {
    EXPECT_TRUE(c.setGoal(goal, now).ok());
    return run(c, f, now, 5.0);
  }

  GripperController c;
  Finger f;
  double now = 0.0;
};

TEST(GripperController, ReachesTheTargetAndSucceeds) {
  Rig rig(true);
  const GripperUpdate u = rig.runGoal({0.01, 5.0});
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_TRUE(u.reached_goal);
  EXPECT_FALSE(u.stalled);
  EXPECT_NEAR(u.position, 0.01, 0.001);
  EXPECT_DOUBLE_EQ(u.command_max_effort, 5.0);
}

TEST(GripperController, ClosingOnAnObjectStallsAndSucceedsWhenStallingIsAllowed) {
  Rig rig(true);
  rig.f.obstacle = 0.02;  // a 4 cm cube
  GripperUpdate u = rig.runGoal({0.0, 0.0});
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_TRUE(u.stalled);
  EXPECT_FALSE(u.reached_goal);
  EXPECT_NEAR(u.position, 0.02, 1e-12);
  // Reached the cube after 0.4 s, then stall_timeout without movement.
  EXPECT_NEAR(rig.now, 0.4 + 0.2, 0.01);
  // max_effort 0 means the URDF effort limit, and the grip keeps squeezing after the goal ended.
  EXPECT_DOUBLE_EQ(u.command_max_effort, 20.0);
  u = rig.c.update(rig.now + 1.0, rig.f.q);
  EXPECT_DOUBLE_EQ(u.command_position, 0.0);
}

TEST(GripperController, AFingerJitteringOnAnObjectStalls) {
  // As measured in the simulator: a 20 um jitter each 1 ms step is a velocity of +-0.02 m/s, 20 times the
  // stall threshold, while the finger goes nowhere.
  Rig rig(true);
  rig.f.obstacle = 0.02;
  rig.f.jitter = 2e-5;
  const GripperUpdate u = rig.runGoal({0.0, 0.0});
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_TRUE(u.stalled);
  EXPECT_NEAR(rig.now, 0.4 + 0.2, 0.01);
}

TEST(GripperController, AFingerRockingOnAnObjectStalls) {
  // A back-and-forth of 2 mm every 0.1 s: the velocity swings up to +-0.06 m/s, 60 times the stall threshold, and
  // the finger keeps moving by more than the threshold allows in stall_timeout, but comes no closer to the target.
  Rig rig(true);
  rig.f.obstacle = 0.02;
  rig.f.rock = 0.002;
  const GripperUpdate u = rig.runGoal({0.0, 0.0});
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_TRUE(u.stalled);
  EXPECT_FALSE(u.reached_goal);
  EXPECT_NEAR(rig.now, 0.4 + 0.2, 0.01);
  EXPECT_GE(u.position, 0.02);
  EXPECT_LE(u.position, 0.022);
}

TEST(GripperController, AFingerCreepingOnAnObjectStalls) {
  // The object gives way at half the threshold speed while the finger rocks on it.
  Rig rig(false);
  rig.f.obstacle = 0.02;
  rig.f.rock = 0.001;
  rig.f.creep = 0.0005;
  const GripperUpdate u = rig.runGoal({0.0, 0.0});
  EXPECT_EQ(u.state, GoalState::kAborted);
  EXPECT_TRUE(u.stalled);
  EXPECT_LT(rig.now, 0.4 + 0.2 + 0.1);
}

TEST(GripperController, AFingerMovingSlowlyButSteadilyIsNotStalled) {
  // Twice the threshold speed: 2 mm/s towards a target 4 mm away takes 2 s, ten stall timeouts.
  Rig rig(false);
  rig.f.speed = 0.002;
  const GripperUpdate u = rig.runGoal({0.036, 0.0});
  EXPECT_TRUE(u.reached_goal);
  EXPECT_FALSE(u.stalled);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
}

TEST(GripperController, StallAbortsWhenStallingIsNotAllowed) {
  Rig rig(false);
  rig.f.obstacle = 0.02;
  const GripperUpdate u = rig.runGoal({0.0, 0.0});
  EXPECT_EQ(u.state, GoalState::kAborted);
  EXPECT_TRUE(u.stalled);
}

TEST(GripperController, RejectsBadGoals) {
  GripperController c(fingerConfig(true));
  EXPECT_NE(c.setGoal({0.05, 0.0}, 0.0).message.find("outside its limits"), std::string::npos);
  EXPECT_NE(c.setGoal({-0.001, 0.0}, 0.0).message.find("outside its limits"), std::string::npos);
  EXPECT_NE(c.setGoal({0.01, -1.0}, 0.0).message.find("negative"), std::string::npos);
  EXPECT_NE(c.setGoal({0.01, 25.0}, 0.0).message.find("exceeds the effort limit"), std::string::npos);
  EXPECT_NE(c.setGoal({std::nan(""), 1.0}, 0.0).message.find("finite"), std::string::npos);
  EXPECT_FALSE(c.setGoal({0.01, 25.0}, 0.0).ok());
  EXPECT_FALSE(c.active());
}

TEST(GripperController, CancelHoldsTheActualPositionAndPreemptionRestartsTheStallClock) {
  Rig rig(true);
  ASSERT_TRUE(rig.c.setGoal({0.0, 0.0}, rig.now).ok());
  run(rig.c, rig.f, rig.now, 0.1);
  rig.c.cancel(rig.f.q);
  EXPECT_EQ(rig.c.state(), GoalState::kCanceled);
  const double held = rig.f.q;
  GripperUpdate u = rig.c.update(rig.now, rig.f.q);
  EXPECT_DOUBLE_EQ(u.command_position, held);
  EXPECT_FALSE(u.finished);

  // A new goal while one is active replaces it.
  ASSERT_TRUE(rig.c.setGoal({0.0, 0.0}, rig.now).ok());
  u = rig.runGoal({0.03, 0.0});
  EXPECT_TRUE(u.reached_goal);
  EXPECT_NEAR(rig.f.q, 0.03, 0.001);
}

TEST(GripperController, BadConfigThrows) {
  GripperControllerConfig c = fingerConfig(true);
  c.effort_limit = 0.0;
  EXPECT_THROW(GripperController{c}, std::invalid_argument);
  c = fingerConfig(true);
  c.lower = 0.1;
  EXPECT_THROW(GripperController{c}, std::invalid_argument);
  c = fingerConfig(true);
  c.goal_tolerance = -1.0;
  EXPECT_THROW(GripperController{c}, std::invalid_argument);
}

}  // namespace
}  // namespace sixdof_core
