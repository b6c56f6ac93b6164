#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_core {
namespace {

constexpr double kDt = 0.001;

TrajectoryControllerConfig twoJointConfig() {
  TrajectoryControllerConfig c;
  c.name = "test_controller";
  c.joints = {"j1", "j2"};
  c.lower_limits = {-1.0, -2.0};
  c.upper_limits = {1.0, 2.0};
  c.path_tolerance = {0.1, 0.1};
  c.goal_tolerance = {0.01, 0.01};
  c.goal_time = 0.5;
  c.stopped_velocity_tolerance = 0.01;
  return c;
}

TrajectoryGoal goalTo(double q1, double q2, double t) {
  TrajectoryGoal g;
  g.joint_names = {"j1", "j2"};
  g.points = {{{q1, q2}, {0.0, 0.0}, {}, t}};
  return g;
}

// A joint-space plant for the controller: kPerfect follows the command exactly, kLag is a first-order
// servo (time constant 1/gain) with velocity feed-forward, kSlow moves towards the command at no more
// than max_speed, kStuck never moves.
struct Plant {
  enum Kind { kPerfect, kLag, kSlow, kStuck } kind = kPerfect;
  double max_speed = 0.5;
  double gain = 20.0;
  std::vector<double> q{0.0, 0.0};
  std::vector<double> v{0.0, 0.0};
  void apply(const TrajectorySample& desired) {
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (kind == kPerfect) {
        q[i] = desired.position[i];
        v[i] = desired.velocity[i];
      } else if (kind == kLag) {
        v[i] = desired.velocity[i] + gain * (desired.position[i] - q[i]);
        q[i] += v[i] * kDt;
      } else if (kind == kSlow) {
        v[i] = std::clamp((desired.position[i] - q[i]) / kDt, -max_speed, max_speed);
        q[i] += v[i] * kDt;
      }
    }
  }
};

// Runs until the goal finishes or max_time passes; returns the finishing update.
TrajectoryUpdate run(TrajectoryController& c, Plant& plant, double& now, double max_time) {
  TrajectoryUpdate u;
  const double end = now + max_time;
  while (now < end) {
    u = c.update(now, plant.q, plant.v);
    plant.apply(u.desired);
    now += kDt;
    if (u.finished) {
      break;
    }
  }
  return u;
}

class TrajectoryControllerTest : public ::testing::Test {
 protected:
  TrajectoryController c{twoJointConfig()};
  Plant plant;
  double now = 10.0;
  void SetUp() override { c.update(now, plant.q, plant.v); }
};

TEST_F(TrajectoryControllerTest, ReachesGoalAndSucceedsAtTheEndTime) {
  ASSERT_TRUE(c.setGoal(goalTo(0.5, -1.0, 1.0), now).ok());
  EXPECT_TRUE(c.active());
  const double start = now;
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_TRUE(u.finished);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_TRUE(u.result.ok());
  EXPECT_NEAR(now - start, 1.0, 2 * kDt);
  EXPECT_NEAR(plant.q[0], 0.5, 1e-9);
  EXPECT_NEAR(plant.q[1], -1.0, 1e-9);
  // Idle afterwards: the final point stays commanded.
  u = c.update(now + 1.0, plant.q, plant.v);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_FALSE(u.finished);
  EXPECT_NEAR(u.desired.position[0], 0.5, 1e-12);
}

TEST_F(TrajectoryControllerTest, LaggingRobotSucceedsWithinGoalTime) {
  plant.kind = Plant::kLag;
  ASSERT_TRUE(c.setGoal(goalTo(0.5, 1.0, 1.0), now).ok());
  const double start = now;
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded) << u.result.message;
  EXPECT_GT(now - start, 1.0);
  EXPECT_LT(now - start, 1.5);
}

TEST_F(TrajectoryControllerTest, GoalToleranceViolatedWithoutGoalTime) {
  plant.kind = Plant::kSlow;  // still off by more than the goal tolerance at the end time
  TrajectoryGoal g = goalTo(0.8, 0.0, 0.5);
  g.goal_time_tolerance = -1.0;  // negative: no extra time
  g.path_tolerance = {{"j1", -1.0, 0.0, 0.0}};
  g.goal_tolerance = {{"j1", 0.001, 0.0, 0.0}};
  ASSERT_TRUE(c.setGoal(g, now).ok());
  const double start = now;
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kAborted);
  EXPECT_EQ(u.result.status, TrajectoryErrorCode::kGoalToleranceViolated);
  EXPECT_NE(u.result.message.find("j1"), std::string::npos) << u.result.message;
  EXPECT_NEAR(now - start, 0.5, 2 * kDt);
}

TEST_F(TrajectoryControllerTest, StoppedVelocityToleranceIsPartOfTheGoal) {
  // The robot sits on the goal but keeps a small velocity: GOAL_TOLERANCE_VIOLATED after goal_time.
  ASSERT_TRUE(c.setGoal(goalTo(0.0, 0.0, 0.2), now).ok());
  plant.kind = Plant::kStuck;
  plant.v = {0.05, 0.0};
  const double start = now;
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.result.status, TrajectoryErrorCode::kGoalToleranceViolated);
  EXPECT_NE(u.result.message.find("velocity"), std::string::npos) << u.result.message;
  EXPECT_NEAR(now - start, 0.2 + 0.5, 2 * kDt);
}

TEST_F(TrajectoryControllerTest, PathToleranceViolatedHoldsTheActualPosition) {
  plant.kind = Plant::kStuck;
  ASSERT_TRUE(c.setGoal(goalTo(0.9, 0.0, 1.0), now).ok());
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kAborted);
  EXPECT_EQ(u.result.status, TrajectoryErrorCode::kPathToleranceViolated);
  EXPECT_NE(u.result.message.find("j1"), std::string::npos) << u.result.message;
  EXPECT_DOUBLE_EQ(u.desired.position[0], 0.0);
  EXPECT_DOUBLE_EQ(c.update(now, plant.q, plant.v).desired.position[0], 0.0);
}

TEST_F(TrajectoryControllerTest, GoalToleranceOverridesConfig) {
  plant.kind = Plant::kStuck;
  TrajectoryGoal g = goalTo(0.9, 0.0, 1.0);
  // -1: no path check at all; a large goal tolerance then accepts the stuck robot.
  g.path_tolerance = {{"j1", -1.0, 0.0, 0.0}};
  g.goal_tolerance = {{"j1", 1.0, 0.0, 0.0}};
  ASSERT_TRUE(c.setGoal(g, now).ok());
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded) << u.result.message;

  // A positive path tolerance tightens the configured one.
  plant.kind = Plant::kLag;
  g = goalTo(0.9, 0.0, 1.0);
  g.path_tolerance = {{"j1", 1e-4, 0.0, 0.0}};
  ASSERT_TRUE(c.setGoal(g, now).ok());
  u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.result.status, TrajectoryErrorCode::kPathToleranceViolated);
}

TEST_F(TrajectoryControllerTest, JointOrderOfTheGoalIsFollowed) {
  TrajectoryGoal g;
  g.joint_names = {"j2", "j1"};
  g.points = {{{1.5, -0.5}, {}, {}, 0.5}};
  ASSERT_TRUE(c.setGoal(g, now).ok());
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(plant.q[0], -0.5, 1e-9);
  EXPECT_NEAR(plant.q[1], 1.5, 1e-9);
}

TEST_F(TrajectoryControllerTest, StartsFromTheCurrentStateAndIsContinuous) {
  plant.q = {0.2, 0.3};
  c.hold(plant.q);
  ASSERT_TRUE(c.setGoal(goalTo(0.6, -0.3, 1.0), now).ok());
  TrajectoryUpdate u = c.update(now, plant.q, plant.v);
  EXPECT_NEAR(u.desired.position[0], 0.2, 1e-12);
  EXPECT_NEAR(u.desired.position[1], 0.3, 1e-12);
  run(c, plant, now, 0.5);
  u = c.update(now, plant.q, plant.v);
  EXPECT_NEAR(u.desired.position[0], 0.4, 2e-3);  // cubic with zero end velocities: halfway at half time
}

TEST_F(TrajectoryControllerTest, FirstPointAtTimeZeroIsCommandedAtOnce) {
  TrajectoryGoal g;
  g.joint_names = {"j1", "j2"};
  g.points = {{{0.05, 0.0}, {}, {}, 0.0}, {{0.1, 0.0}, {}, {}, 1.0}};
  ASSERT_TRUE(c.setGoal(g, now).ok());
  EXPECT_NEAR(c.update(now, plant.q, plant.v).desired.position[0], 0.05, 1e-12);
}

TEST_F(TrajectoryControllerTest, PreemptionContinuesFromTheCurrentDesiredState) {
  ASSERT_TRUE(c.setGoal(goalTo(0.8, 0.0, 1.0), now).ok());
  run(c, plant, now, 0.4);
  const TrajectoryUpdate before = c.update(now, plant.q, plant.v);
  ASSERT_TRUE(c.setGoal(goalTo(-0.5, 1.0, 1.0), now).ok());
  const TrajectoryUpdate after = c.update(now, plant.q, plant.v);
  EXPECT_NEAR(after.desired.position[0], before.desired.position[0], 1e-12);
  EXPECT_NEAR(after.desired.velocity[0], before.desired.velocity[0], 1e-12);
  EXPECT_GT(before.desired.velocity[0], 0.1);
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(plant.q[0], -0.5, 1e-9);
}

TEST_F(TrajectoryControllerTest, CancelHoldsTheActualPosition) {
  ASSERT_TRUE(c.setGoal(goalTo(0.8, 0.0, 1.0), now).ok());
  run(c, plant, now, 0.5);
  const std::vector<double> at_cancel = plant.q;
  c.cancel(plant.q);
  EXPECT_EQ(c.state(), GoalState::kCanceled);
  for (int i = 0; i < 100; ++i) {
    TrajectoryUpdate u = c.update(now, plant.q, plant.v);
    plant.apply(u.desired);
    now += kDt;
    EXPECT_FALSE(u.finished);
  }
  EXPECT_NEAR(plant.q[0], at_cancel[0], 1e-12);
}

TEST_F(TrajectoryControllerTest, EmptyTrajectoryStopsAndSucceeds) {
  ASSERT_TRUE(c.setGoal(goalTo(0.8, 0.0, 1.0), now).ok());
  run(c, plant, now, 0.5);
  const double q_stop = plant.q[0];
  ASSERT_TRUE(c.setGoal(TrajectoryGoal{}, now).ok());
  TrajectoryUpdate u = run(c, plant, now, 1.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(plant.q[0], q_stop, 1e-12);
}

TEST_F(TrajectoryControllerTest, InvalidJointsAreRejectedByName) {
  TrajectoryGoal g = goalTo(0.1, 0.1, 1.0);
  g.joint_names = {"j1", "elbow"};
  TrajectoryResult r = c.setGoal(g, now);
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidJoints);
  EXPECT_NE(r.message.find("elbow"), std::string::npos) << r.message;

  g.joint_names = {"j1", "j1"};
  r = c.setGoal(g, now);
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidJoints);
  EXPECT_NE(r.message.find("twice"), std::string::npos) << r.message;

  g.joint_names = {"j1"};
  g.points = {{{0.1}, {}, {}, 1.0}};
  r = c.setGoal(g, now);
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidJoints);
  EXPECT_NE(r.message.find("j2"), std::string::npos) << r.message;

  g = goalTo(0.1, 0.1, 1.0);
  g.goal_tolerance = {{"wrist", 0.1, 0.0, 0.0}};
  EXPECT_EQ(c.setGoal(g, now).status, TrajectoryErrorCode::kInvalidJoints);
  EXPECT_FALSE(c.active());
}

TEST_F(TrajectoryControllerTest, InvalidGoalsAreRejectedWithTheReason) {
  const auto expectInvalid = [&](const TrajectoryGoal& g, const std::string& needle) {
    TrajectoryResult r = c.setGoal(g, now);
    EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidGoal) << needle;
    EXPECT_NE(r.message.find(needle), std::string::npos) << r.message;
  };
  TrajectoryGoal g = goalTo(std::nan(""), 0.0, 1.0);
  expectInvalid(g, "NaN");
  g = goalTo(0.0, std::numeric_limits<double>::infinity(), 1.0);
  expectInvalid(g, "inf");
  g = goalTo(1.5, 0.0, 1.0);
  expectInvalid(g, "outside its limits");
  // A rounding error past a limit shows in full.
  g = goalTo(std::nextafter(1.0, 2.0), 0.0, 1.0);
  expectInvalid(g, "position 1.0000000000000002 of joint 'j1' is outside its limits [-1, 1]");
  g = goalTo(0.0, 0.0, 1.0);
  g.points.push_back({{0.1, 0.1}, {}, {}, 1.0});
  expectInvalid(g, "strictly increase");
  g.points.back().time_from_start = 0.5;
  expectInvalid(g, "strictly increase");
  g = goalTo(0.0, 0.0, -1.0);
  expectInvalid(g, "time_from_start");
  g = goalTo(0.0, 0.0, 1.0);
  g.points[0].positions.pop_back();
  expectInvalid(g, "1 positions for 2 joints");
  g = goalTo(0.0, 0.0, 1.0);
  g.points[0].velocities = {0.0};
  expectInvalid(g, "velocities");
  g = goalTo(0.0, 0.0, 1.0);
  g.points[0].accelerations = {0.0, 0.0, 0.0};
  expectInvalid(g, "accelerations");
  g = goalTo(0.0, 0.0, 1.0);
  g.path_tolerance = {{"j1", -0.5, 0.0, 0.0}};
  expectInvalid(g, "path_tolerance");
  EXPECT_FALSE(c.active());
}

TEST_F(TrajectoryControllerTest, RejectedGoalDoesNotDisturbTheActiveOne) {
  ASSERT_TRUE(c.setGoal(goalTo(0.5, 0.0, 1.0), now).ok());
  run(c, plant, now, 0.3);
  EXPECT_FALSE(c.setGoal(goalTo(5.0, 0.0, 1.0), now).ok());
  EXPECT_TRUE(c.active());
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(plant.q[0], 0.5, 1e-9);
}

TEST_F(TrajectoryControllerTest, HeaderStampSchedulesTheTrajectory) {
  TrajectoryGoal g = goalTo(0.5, 0.0, 1.0);
  g.start_time = now - 5.0;
  EXPECT_EQ(c.setGoal(g, now).status, TrajectoryErrorCode::kOldHeaderTimestamp);
  g.start_time = now + 1.0;
  ASSERT_TRUE(c.setGoal(g, now).ok());
  const double start = now;
  TrajectoryUpdate u = run(c, plant, now, 5.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(now - start, 2.0, 2 * kDt);
}

TEST_F(TrajectoryControllerTest, PointsAlreadyInThePastAreSkipped) {
  TrajectoryGoal g;
  g.joint_names = {"j1", "j2"};
  g.points = {{{0.9, 0.0}, {}, {}, 1.0}, {{0.5, 0.0}, {}, {}, 3.0}};
  g.start_time = now - 2.0;  // the first point is 1 s in the past, the last 1 s ahead
  ASSERT_TRUE(c.setGoal(g, now).ok());
  const double start = now;
  double highest = 0.0;
  TrajectoryUpdate u;
  while (!u.finished && now < start + 5.0) {
    u = c.update(now, plant.q, plant.v);
    plant.apply(u.desired);
    highest = std::max(highest, plant.q[0]);
    now += kDt;
  }
  EXPECT_EQ(u.state, GoalState::kSucceeded);
  EXPECT_NEAR(now - start, 1.0, 5 * kDt);  // fixed steps accumulate round-off in `now`
  EXPECT_NEAR(highest, 0.5, 1e-9);  // straight from the current state to the last point
}

TEST(TrajectoryControllerConfig, BadConfigThrows) {
  TrajectoryControllerConfig c = twoJointConfig();
  c.joints = {"j1", "j1"};
  EXPECT_THROW(TrajectoryController{c}, std::invalid_argument);
  c = twoJointConfig();
  c.goal_tolerance = {0.1};
  EXPECT_THROW(TrajectoryController{c}, std::invalid_argument);
  c = twoJointConfig();
  c.path_tolerance = {-0.1, 0.1};
  EXPECT_THROW(TrajectoryController{c}, std::invalid_argument);
  c = twoJointConfig();
  c.lower_limits = {2.0, -2.0};
  EXPECT_THROW(TrajectoryController{c}, std::invalid_argument);
  c = twoJointConfig();
  c.joints.clear();
  EXPECT_THROW(TrajectoryController{c}, std::invalid_argument);
}

TEST_F(TrajectoryControllerTest, SampleIsWhatUpdateCommandsAtThatTime) {
  // Holding: any time gives the held position at rest.
  std::optional<TrajectorySample> held = c.sample(now + 100.0);
  ASSERT_TRUE(held);
  EXPECT_EQ(held->position, plant.q);
  EXPECT_EQ(held->velocity, std::vector<double>({0.0, 0.0}));
  ASSERT_TRUE(c.setGoal(goalTo(0.5, -1.0, 1.0), now).ok());
  // Ahead of time: the end of the trajectory, midway, and after its end.
  const std::optional<TrajectorySample> end = c.sample(now + 1.0);
  const std::optional<TrajectorySample> mid = c.sample(now + 0.5);
  const std::optional<TrajectorySample> after = c.sample(now + 3.0);
  ASSERT_TRUE(end && mid && after);
  EXPECT_NEAR(end->position[0], 0.5, 1e-12);
  EXPECT_NEAR(end->position[1], -1.0, 1e-12);
  EXPECT_EQ(after->position, end->position);
  EXPECT_GT(mid->velocity[0], 0.0);
  const double mid_time = now + 0.5;
  while (now < mid_time - kDt / 2) {
    plant.apply(c.update(now, plant.q, plant.v).desired);
    now += kDt;
  }
  const TrajectoryUpdate u = c.update(mid_time, plant.q, plant.v);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(u.desired.position[i], mid->position[i], 1e-12);
    EXPECT_NEAR(u.desired.velocity[i], mid->velocity[i], 1e-12);
    EXPECT_NEAR(u.desired.acceleration[i], mid->acceleration[i], 1e-12);
  }
}

// j1 brakes onto its upper limit (as at the end of a blend arc) 0.03 s after the first point and stays there (a
// straight segment along the limit): its acceleration jumps from -2 to 0 between the points, 0.1 s apart as
// move_group's, and the quintic through them passes the limit by ~2e-4 rad though both points are within it. The
// controller's commands stay within the limits and still pass through every point.
TEST_F(TrajectoryControllerTest, CommandsBetweenPointsWithinTheLimitsStayWithinThem) {
  const double upper = twoJointConfig().upper_limits[0];
  TrajectoryGoal g;
  g.joint_names = {"j1", "j2"};
  g.points = {{{upper - 0.0009, 0.0}, {0.06, 0.2}, {-2.0, 0.0}, 0.0},
              {{upper, 0.02}, {0.0, 0.2}, {0.0, 0.0}, 0.1},
              {{upper, 0.04}, {0.0, 0.0}, {0.0, 0.0}, 0.2}};
  const Trajectory t{g.joint_names, g.points};
  const TrajectorySampler unbounded(t);
  double overshoot = 0.0;
  for (double time = 0.0; time <= t.duration(); time += kDt / 4) {
    overshoot = std::max(overshoot, unbounded.sample(time).position[0] - upper);
  }
  ASSERT_GT(overshoot, 1e-4) << "the points no longer reproduce the quintic's overshoot";

  plant.q = g.points.front().positions;
  c.hold(plant.q);
  ASSERT_TRUE(c.setGoal(g, now).ok());
  const double start = now;
  for (double time = 0.0; time <= t.duration(); time += kDt / 4) {
    const std::optional<TrajectorySample> s = c.sample(start + time);
    ASSERT_TRUE(s);
    ASSERT_LE(s->position[0], upper) << "t=" << time;
  }
  for (const TrajectoryPoint& p : t.points) {
    EXPECT_EQ(c.sample(start + p.time_from_start)->position, p.positions);
  }
  const TrajectoryUpdate u = run(c, plant, now, t.duration() + 1.0);
  EXPECT_EQ(u.state, GoalState::kSucceeded) << u.result.message;
}

TEST(TrajectoryControllerNoState, GoalBeforeAnyUpdateIsRejected) {
  TrajectoryController c{twoJointConfig()};
  EXPECT_FALSE(c.sample(0.0));
  TrajectoryResult r = c.setGoal(goalTo(0.1, 0.1, 1.0), 0.0);
  EXPECT_EQ(r.status, TrajectoryErrorCode::kInvalidGoal);
  EXPECT_NE(r.message.find("no current state"), std::string::npos);
}

}  // namespace
}  // namespace sixdof_core
