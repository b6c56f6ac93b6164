// Time-optimal parameterization: limits are checked on every output point at 1 ms resolution, against
// the limits themselves (the solver keeps a 0.1% margin), plus finite differences of the output, so
// the reported velocities/accelerations cannot understate the motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sixdof_core/time_parameterization.h"

namespace sixdof_core {
namespace {

const std::vector<std::string> kJoints = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"};

TimeParameterizationOptions armOptions() {
  TimeParameterizationOptions o;
  o.max_velocity = {2.0, 2.0, 2.0, 3.0, 3.0, 3.0};
  o.max_acceleration = {3.0, 2.5, 4.0, 6.0, 5.0, 8.0};
  o.sample_period = 0.001;
  o.max_deviation = 0.05;
  return o;
}

std::vector<std::vector<double>> randomPath(std::mt19937* rng, int count) {
  std::uniform_real_distribution<double> q(-2.0, 2.0);
  std::vector<std::vector<double>> path(count, std::vector<double>(kJoints.size()));
  for (auto& w : path) {
    for (double& v : w) v = q(*rng);
  }
  return path;
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(sum);
}

// Every property the planner and the controllers rely on.
void expectValid(const Trajectory& t, const std::vector<std::vector<double>>& waypoints,
                 const TimeParameterizationOptions& o) {
  ASSERT_EQ(validateTrajectory(t), "");
  const std::size_t n = kJoints.size();
  const auto& first = t.points.front();
  const auto& last = t.points.back();
  EXPECT_EQ(first.time_from_start, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    EXPECT_NEAR(first.positions[j], waypoints.front()[j], 1e-12);
    EXPECT_NEAR(last.positions[j], waypoints.back()[j], 1e-12);
    EXPECT_EQ(first.velocities[j], 0.0);
    EXPECT_EQ(last.velocities[j], 0.0);
  }
  double worst_v = 0.0, worst_a = 0.0, worst_fd_v = 0.0, worst_fd_a = 0.0, max_step = 0.0;
  for (std::size_t k = 0; k < t.points.size(); ++k) {
    const auto& p = t.points[k];
    for (std::size_t j = 0; j < n; ++j) {
      const double vmax = o.max_velocity[j] * o.velocity_scaling;
      const double amax = o.max_acceleration[j] * o.acceleration_scaling;
      worst_v = std::max(worst_v, std::abs(p.velocities[j]) / vmax);
      worst_a = std::max(worst_a, std::abs(p.accelerations[j]) / amax);
      if (k + 1 < t.points.size()) {
        const auto& q = t.points[k + 1];
        const double dt = q.time_from_start - p.time_from_start;
        ASSERT_GT(dt, 0.0);
        ASSERT_LE(dt, o.sample_period + 1e-12);
        worst_fd_v = std::max(worst_fd_v, std::abs(q.positions[j] - p.positions[j]) / dt / vmax);
        worst_fd_a = std::max(worst_fd_a, std::abs(q.velocities[j] - p.velocities[j]) / dt / amax);
      }
    }
    if (k + 1 < t.points.size()) max_step = std::max(max_step, distance(p.positions, t.points[k + 1].positions));
  }
  EXPECT_LE(worst_v, 1.0);
  EXPECT_LE(worst_a, 1.0);
  EXPECT_LE(worst_fd_v, 1.0);
  EXPECT_LE(worst_fd_a, 1.0);
  // Time-optimal: some joint runs at (almost) its velocity or acceleration limit.
  EXPECT_GT(std::max(worst_v, worst_a), 0.99);
  // Interior waypoints: the path passes within max_deviation; samples are at most max_step apart.
  for (std::size_t w = 1; w + 1 < waypoints.size(); ++w) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& p : t.points) nearest = std::min(nearest, distance(p.positions, waypoints[w]));
    EXPECT_LE(nearest, o.max_deviation + 0.5 * max_step + 1e-9) << "waypoint " << w;
  }
}

TEST(TimeParameterization, RandomPathsRespectLimits) {
  std::mt19937 rng(2024);
  const TimeParameterizationOptions o = armOptions();
  for (int trial = 0; trial < 12; ++trial) {
    const auto path = randomPath(&rng, 2 + trial % 6);
    const TimeParameterizationResult r = computeTimeOptimalTrajectory(kJoints, path, o);
    ASSERT_TRUE(r.ok()) << r.message;
    SCOPED_TRACE("trial " + std::to_string(trial));
    expectValid(r.trajectory, path, o);
  }
}

TEST(TimeParameterization, DenseSmallStepPathLikeAPlannerOutput) {
  // Many short collinear-ish segments (an interpolated plan) with jitter.
  std::mt19937 rng(5);
  std::normal_distribution<double> jitter(0.0, 0.002);
  std::vector<std::vector<double>> path;
  for (int k = 0; k <= 60; ++k) {
    std::vector<double> w(kJoints.size());
    for (std::size_t j = 0; j < w.size(); ++j) w[j] = std::sin(0.05 * k + j) + jitter(rng);
    path.push_back(w);
  }
  const TimeParameterizationOptions o = armOptions();
  const TimeParameterizationResult r = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(r.ok()) << r.message;
  expectValid(r.trajectory, path, o);
}

TEST(TimeParameterization, StaysWithinTheWaypointsRangeOfEachJoint) {
  // Random walks with joint4 at or just below pi (its limit), each parameterized twice: the second time over the
  // first one's dense samples, whose corners are nearly straight (a Cartesian path retimed to other scaling
  // factors). No position may leave the waypoints' range, not even by rounding: a controller refuses pi + 1e-16.
  std::mt19937 rng(11);
  std::normal_distribution<double> step(0.0, 0.02);
  std::normal_distribution<double> below(0.0, 0.01);
  std::uniform_int_distribution<int> count(3, 40);
  TimeParameterizationOptions slow = armOptions();
  slow.velocity_scaling = slow.acceleration_scaling = 0.1;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<std::vector<double>> path(count(rng), std::vector<double>(kJoints.size(), 0.0));
    for (std::size_t k = 0; k < path.size(); ++k) {
      for (std::size_t j = 0; j < kJoints.size(); ++j) path[k][j] = (k > 0 ? path[k - 1][j] : 0.0) + step(rng);
      path[k][3] = M_PI - (k % 2 == 0 ? 0.0 : std::abs(below(rng)));
    }
    const TimeParameterizationResult once = computeTimeOptimalTrajectory(kJoints, path, armOptions());
    ASSERT_TRUE(once.ok()) << once.message;
    std::vector<std::vector<double>> samples;
    for (const auto& point : once.trajectory.points) samples.push_back(point.positions);
    const TimeParameterizationResult twice = computeTimeOptimalTrajectory(kJoints, samples, slow);
    ASSERT_TRUE(twice.ok()) << twice.message;
    for (std::size_t j = 0; j < kJoints.size(); ++j) {
      double lo = path[0][j], hi = path[0][j];
      for (const auto& w : path) {
        lo = std::min(lo, w[j]);
        hi = std::max(hi, w[j]);
      }
      for (const Trajectory* t : {&once.trajectory, &twice.trajectory}) {
        for (const auto& point : t->points) {
          ASSERT_GE(point.positions[j], lo) << "trial " << trial << " joint " << j;
          ASSERT_LE(point.positions[j], hi) << "trial " << trial << " joint " << j;
        }
      }
    }
  }
}

TEST(TimeParameterization, NearlyStraightCornerStaysOnThePath) {
  // Three samples of an earlier parameterization (a retimed path): the corner turns by about 1e-8 rad. Its blend's
  // radius is then huge, and an arc written from its centre gave positions of 10^4 rad.
  const std::vector<std::vector<double>> path = {
      {-0.08487150550100575, 0.046231422672101785, 0.08630041970398288, 3.1327754548765046, -0.04583224436218221,
       -0.16777538938542458},
      {-0.08525677448797624, 0.046866950106313705, 0.08715274476331113, 3.1325652222371128, -0.04744210388716565,
       -0.16786312418444968},
      {-0.08564204347494672, 0.047502477540525626, 0.08800506982263938, 3.132354989597721, -0.0490519634121491,
       -0.16795085898347478}};
  TimeParameterizationOptions slow = armOptions();
  slow.max_velocity.assign(kJoints.size(), 2.0);
  slow.max_acceleration.assign(kJoints.size(), 3.0);
  slow.velocity_scaling = 0.1;
  const TimeParameterizationResult r = computeTimeOptimalTrajectory(kJoints, path, slow);
  ASSERT_TRUE(r.ok()) << r.message;
  for (const auto& point : r.trajectory.points) {
    for (std::size_t j = 0; j < kJoints.size(); ++j) {
      EXPECT_GE(point.positions[j], std::min(path.front()[j], path.back()[j]) - 1e-12);
      EXPECT_LE(point.positions[j], std::max(path.front()[j], path.back()[j]) + 1e-12);
    }
  }
}

TEST(TimeParameterization, MatchesTrapezoidalOptimumOnAStraightMove) {
  TimeParameterizationOptions o;
  o.max_velocity = {1.0};
  o.max_acceleration = {2.0};
  o.sample_period = 0.001;
  // Trapezoid: 2 rad at 1 rad/s with 2 rad/s^2 takes D/v + v/a = 2.5 s.
  auto r = computeTimeOptimalTrajectory({"j"}, {{0.0}, {2.0}}, o);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_NEAR(r.trajectory.duration(), 2.5, 2.5 * 2e-3);
  // Triangle: 0.5 rad with 2 rad/s^2 (never reaching 1 rad/s) takes 2 sqrt(D / a) = 1 s.
  r = computeTimeOptimalTrajectory({"j"}, {{0.0}, {0.5}}, o);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.trajectory.duration(), 1.0, 1.0 * 2e-3);
  // Collinear waypoints are not stops.
  r = computeTimeOptimalTrajectory({"j"}, {{0.0}, {0.5}, {1.0}, {2.0}}, o);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.trajectory.duration(), 2.5, 2.5 * 2e-3);
}

TEST(TimeParameterization, ScalingFactorsScaleDuration) {
  std::mt19937 rng(11);
  const auto path = randomPath(&rng, 4);
  TimeParameterizationOptions o = armOptions();
  const auto full = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(full.ok());
  // Velocity x f and acceleration x f^2 is the same motion 1/f times slower.
  o.velocity_scaling = 0.5;
  o.acceleration_scaling = 0.25;
  const auto slow = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(slow.ok());
  EXPECT_NEAR(slow.trajectory.duration() / full.trajectory.duration(), 2.0, 2e-3);
  expectValid(slow.trajectory, path, o);
  // Velocity scaling alone: never faster than the scaled limit, and slower overall.
  o.acceleration_scaling = 1.0;
  o.velocity_scaling = 0.3;
  const auto capped = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(capped.ok());
  expectValid(capped.trajectory, path, o);
  EXPECT_GT(capped.trajectory.duration(), full.trajectory.duration());
}

TEST(TimeParameterization, StopsAtReversalsAndUnblendedCorners) {
  TimeParameterizationOptions o = armOptions();
  std::vector<std::vector<double>> path = {std::vector<double>(6, 0.0), std::vector<double>(6, 0.0),
                                           std::vector<double>(6, 0.0)};
  path[1][0] = 1.0;   // out along joint1 ...
  path[2][0] = 0.2;   // ... and back: a reversal cannot be blended
  path[2][1] = 0.0;
  auto r = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(r.ok()) << r.message;
  double reach = 0.0;
  for (const auto& p : r.trajectory.points) reach = std::max(reach, p.positions[0]);
  // The path turns exactly at the waypoint; 1 ms samples land within 1e-6 of the turning instant's state.
  EXPECT_NEAR(reach, 1.0, 1e-6);
  expectValid(r.trajectory, path, o);

  // A right-angle corner: blended (faster) vs max_deviation 0 (exact stop at the corner).
  path[2][0] = 1.0;
  path[2][1] = 1.0;
  const auto blended = computeTimeOptimalTrajectory(kJoints, path, o);
  o.max_deviation = 0.0;
  const auto sharp = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(blended.ok() && sharp.ok());
  EXPECT_LT(blended.trajectory.duration(), sharp.trajectory.duration());
  double nearest = 1.0;
  for (const auto& p : sharp.trajectory.points) nearest = std::min(nearest, distance(p.positions, path[1]));
  EXPECT_LT(nearest, 1e-4);
  expectValid(sharp.trajectory, path, o);
}

TEST(TimeParameterization, NearReversalsAndTinySegments) {
  const TimeParameterizationOptions o = armOptions();
  std::vector<std::vector<double>> path = {std::vector<double>(6, 0.0)};
  // Out and almost straight back (1e-4 rad off a reversal), then a zig-zag of 1e-4 rad steps.
  std::vector<double> w(6, 0.0);
  w[0] = 1.0;
  path.push_back(w);
  w[0] = 0.0;
  w[1] = 1e-4;
  path.push_back(w);
  for (int k = 0; k < 20; ++k) {
    w[2] += 1e-4;
    w[3] = (k % 2) ? 0.0 : 1e-4;
    path.push_back(w);
  }
  w[4] = 0.5;
  path.push_back(w);
  const TimeParameterizationResult r = computeTimeOptimalTrajectory(kJoints, path, o);
  ASSERT_TRUE(r.ok()) << r.message;
  expectValid(r.trajectory, path, o);
}

TEST(TimeParameterization, SinglePointAndDuplicates) {
  const TimeParameterizationOptions o = armOptions();
  const std::vector<double> q(6, 0.3);
  auto r = computeTimeOptimalTrajectory(kJoints, {q}, o);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.trajectory.points.size(), 1u);
  EXPECT_EQ(r.trajectory.points[0].positions, q);
  EXPECT_EQ(r.trajectory.points[0].velocities, std::vector<double>(6, 0.0));
  r = computeTimeOptimalTrajectory(kJoints, {q, q, q}, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.trajectory.points.size(), 1u);
  std::vector<double> q2(6, 0.8);
  r = computeTimeOptimalTrajectory(kJoints, {q, q, q2, q2}, o);
  ASSERT_TRUE(r.ok());
  expectValid(r.trajectory, {q, q2}, o);
}

TEST(TimeParameterization, RejectsInvalidInput) {
  const std::vector<std::vector<double>> path = {std::vector<double>(6, 0.0), std::vector<double>(6, 1.0)};
  auto expectRejected = [&](const std::vector<std::string>& names, const std::vector<std::vector<double>>& p,
                            const TimeParameterizationOptions& o, const std::string& needle) {
    const auto r = computeTimeOptimalTrajectory(names, p, o);
    EXPECT_EQ(r.status, TimeParameterizationStatus::kInvalidInput) << needle;
    EXPECT_NE(r.message.find(needle), std::string::npos) << r.message;
    EXPECT_TRUE(r.trajectory.points.empty());
  };
  for (double f : {0.0, -0.5, 1.5, std::nan("")}) {
    TimeParameterizationOptions o = armOptions();
    o.velocity_scaling = f;
    expectRejected(kJoints, path, o, "velocity scaling factor must be in (0, 1]");
    o = armOptions();
    o.acceleration_scaling = f;
    expectRejected(kJoints, path, o, "acceleration scaling factor must be in (0, 1]");
  }
  TimeParameterizationOptions o = armOptions();
  expectRejected(kJoints, {}, o, "no waypoints");
  expectRejected({}, path, o, "no joint names");
  expectRejected({"a", "a", "b", "c", "d", "e"}, path, o, "duplicate joint names");
  expectRejected(kJoints, {std::vector<double>(6, 0.0), std::vector<double>(5, 0.0)}, o, "waypoint 1 has 5 values");
  expectRejected(kJoints, {std::vector<double>(6, 0.0), std::vector<double>(6, INFINITY)}, o, "not finite");
  o.max_velocity[2] = 0.0;
  expectRejected(kJoints, path, o, "max_velocity of joint3");
  o = armOptions();
  o.max_acceleration.pop_back();
  expectRejected(kJoints, path, o, "need 6 values");
  o = armOptions();
  o.max_deviation = -1.0;
  expectRejected(kJoints, path, o, "max_deviation");
  o = armOptions();
  o.sample_period = 0.0;
  expectRejected(kJoints, path, o, "sample_period");
}

}  // namespace
}  // namespace sixdof_core
