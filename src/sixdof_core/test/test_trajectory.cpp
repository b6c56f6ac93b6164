// Trajectory validation, spline segments and sampling (the interpolation a joint_trajectory_controller applies).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "sixdof_core/time_parameterization.h"
#include "sixdof_core/trajectory.h"

namespace sixdof_core {
namespace {

TrajectoryPoint point(double t, std::vector<double> q, std::vector<double> v = {}, std::vector<double> a = {}) {
  TrajectoryPoint p;
  p.time_from_start = t;
  p.positions = std::move(q);
  p.velocities = std::move(v);
  p.accelerations = std::move(a);
  return p;
}

TEST(Trajectory, ValidationNamesTheProblem) {
  Trajectory t;
  EXPECT_EQ(validateTrajectory(t), "trajectory has no joint names");
  t.joint_names = {"a", "b"};
  EXPECT_EQ(validateTrajectory(t), "trajectory has no points");
  t.points = {point(0.0, {0, 0}), point(1.0, {1})};
  EXPECT_NE(validateTrajectory(t).find("point 1: positions size"), std::string::npos);
  t.points = {point(0.0, {0, 0}), point(0.0, {1, 1})};
  EXPECT_NE(validateTrajectory(t).find("not strictly increasing"), std::string::npos);
  t.points = {point(0.0, {0, 0}, {0, 0}), point(1.0, {1, 1})};
  EXPECT_NE(validateTrajectory(t).find("velocities size is inconsistent"), std::string::npos);
  t.points = {point(0.0, {0, NAN})};
  EXPECT_NE(validateTrajectory(t).find("non-finite"), std::string::npos);
  t.points = {point(-1.0, {0, 0})};
  EXPECT_NE(validateTrajectory(t).find("time_from_start"), std::string::npos);
  t.points = {point(0.0, {0, 0}), point(0.5, {1, 1})};
  EXPECT_EQ(validateTrajectory(t), "");
}

TEST(Trajectory, SamplingReproducesPolynomials) {
  // q(t) = 1 + 2t - t^2 + 0.5 t^3 - 0.25 t^4 + 0.1 t^5: the quintic from its end states is q itself.
  auto q = [](double t) { return 1 + 2 * t - t * t + 0.5 * t * t * t - 0.25 * std::pow(t, 4) + 0.1 * std::pow(t, 5); };
  auto v = [](double t) { return 2 - 2 * t + 1.5 * t * t - std::pow(t, 3) + 0.5 * std::pow(t, 4); };
  auto a = [](double t) { return -2 + 3 * t - 3 * t * t + 2 * std::pow(t, 3); };
  const TrajectorySampler quintic(
      {{"j"}, {point(0.5, {q(0.5)}, {v(0.5)}, {a(0.5)}), point(2.0, {q(2.0)}, {v(2.0)}, {a(2.0)})}});
  EXPECT_EQ(quintic.segmentType(0), InterpolationType::kQuintic);
  for (double t : {0.5, 0.9, 1.3, 1.77, 2.0}) {
    const TrajectorySample s = quintic.sample(t);
    EXPECT_NEAR(s.position[0], q(t), 1e-9);
    EXPECT_NEAR(s.velocity[0], v(t), 1e-9);
    EXPECT_NEAR(s.acceleration[0], a(t), 1e-9);
  }

  // Cubic with velocities only: q = t^3 - t on [0, 1].
  const TrajectorySampler cubic({{"j"}, {point(0.0, {0.0}, {-1.0}), point(1.0, {0.0}, {2.0})}});
  EXPECT_EQ(cubic.segmentType(0), InterpolationType::kCubic);
  const TrajectorySample c = cubic.sample(0.5);
  EXPECT_NEAR(c.position[0], 0.125 - 0.5, 1e-12);
  EXPECT_NEAR(c.velocity[0], 0.75 - 1.0, 1e-12);
  EXPECT_NEAR(c.acceleration[0], 3.0, 1e-12);

  // Linear with positions only.
  const TrajectorySampler linear({{"a", "b"}, {point(0.0, {0.0, 1.0}), point(2.0, {1.0, -1.0})}});
  const TrajectorySample l = linear.sample(0.5);
  EXPECT_NEAR(l.position[0], 0.25, 1e-12);
  EXPECT_NEAR(l.position[1], 0.5, 1e-12);
  EXPECT_NEAR(l.velocity[1], -1.0, 1e-12);
}

// joint_trajectory_controller's semantics outside the points' times: the first or last point, at rest.
TEST(Trajectory, SamplingHoldsAtRestOutsideThePoints) {
  const TrajectorySampler t({{"a", "b"},
                             {point(1.0, {0.0, 1.0}, {0.0, 0.0}), point(2.0, {1.0, 0.0}, {0.5, 0.0}),
                              point(4.0, {2.0, -1.0}, {0.3, 0.0})}});
  EXPECT_EQ(t.segmentCount(), 2u);
  EXPECT_DOUBLE_EQ(t.startTime(), 1.0);
  EXPECT_DOUBLE_EQ(t.endTime(), 4.0);
  const TrajectorySample knot = t.sample(2.0);
  EXPECT_NEAR(knot.position[0], 1.0, 1e-12);
  EXPECT_NEAR(knot.velocity[0], 0.5, 1e-12);
  const TrajectorySample before = t.sample(-3.0);
  EXPECT_EQ(before.position, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(before.velocity, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(before.acceleration, (std::vector<double>{0.0, 0.0}));
  // At the last point's time the point as given; after it the point's positions at rest.
  const TrajectorySample end = t.sample(4.0);
  EXPECT_EQ(end.position, (std::vector<double>{2.0, -1.0}));
  EXPECT_EQ(end.velocity, (std::vector<double>{0.3, 0.0}));
  const TrajectorySample after = t.sample(4.001);
  EXPECT_EQ(after.position, (std::vector<double>{2.0, -1.0}));
  EXPECT_EQ(after.velocity, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(after.acceleration, (std::vector<double>{0.0, 0.0}));
  // Inside a segment the sample lies between the points for this monotone profile.
  const TrajectorySample mid = t.sample(3.0);
  EXPECT_GT(mid.position[0], 1.0);
  EXPECT_LT(mid.position[0], 2.0);
  EXPECT_THROW(t.sample(NAN), std::invalid_argument);

  const TrajectorySampler single({{"j"}, {point(0.0, {0.7})}});
  EXPECT_EQ(single.segmentCount(), 0u);
  for (double time : {-1.0, 0.0, 5.0}) {
    EXPECT_EQ(single.sample(time).position, std::vector<double>{0.7});
    EXPECT_EQ(single.sample(time).velocity, std::vector<double>{0.0});
  }
}

TEST(Trajectory, SamplerRejectsMalformedTrajectoriesByName) {
  const auto problem = [](const Trajectory& t) {
    try {
      TrajectorySampler{t};
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(problem({{"j"}, {}}).find("no points"), std::string::npos);
  EXPECT_NE(problem({{"j"}, {point(0.0, {0.0}), point(0.0, {1.0})}}).find("not strictly increasing"),
            std::string::npos);
  EXPECT_NE(problem({{"j"}, {point(0.0, {0.0}), point(1.0, {1.0, 2.0})}}).find("positions size"), std::string::npos);
  EXPECT_NE(problem({{"j"}, {point(0.0, {0.0}, {1.0, 2.0})}}).find("velocities size"), std::string::npos);
  EXPECT_NE(problem({{"j"}, {point(NAN, {0.0})}}).find("time_from_start must be finite"), std::string::npos);
  // Unlike validateTrajectory: negative times (a controller's clock) and derivatives on some points only.
  EXPECT_EQ(problem({{"j"}, {point(-2.0, {0.0}, {0.0}), point(-1.0, {1.0})}}), "");
}

TEST(Trajectory, BoundedSamplingKeepsSegmentsBetweenInBoundPointsWithinTheBounds) {
  // j's quintic starts at its upper bound accelerating outwards; k's first point is outside its bounds.
  const Trajectory t{{"j", "k"},
                     {point(0.0, {1.0, 2.5}, {0.0, 0.0}, {2.0, 0.0}), point(1.0, {1.0, 1.5}, {0.0, 0.0}, {0.0, 0.0})}};
  const TrajectorySampler unbounded(t);
  const TrajectorySampler bounded(t, {-1.0, -2.0}, {1.0, 2.0});
  EXPECT_GT(unbounded.sample(0.2).position[0], 1.0);
  const TrajectorySample s = bounded.sample(0.2);
  EXPECT_EQ(s.position[0], 1.0);
  EXPECT_EQ(s.velocity[0], 0.0);
  EXPECT_EQ(s.acceleration[0], 0.0);
  // A segment leaving a point outside the bounds is sampled as given; the points themselves are never moved.
  EXPECT_EQ(s.position[1], unbounded.sample(0.2).position[1]);
  EXPECT_EQ(bounded.sample(0.0).position, t.points[0].positions);
  EXPECT_THROW(TrajectorySampler(t, {-1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(TrajectorySampler(t, {-1.0, 3.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(TrajectorySampler(t, {-1.0, std::nan("")}, {1.0, 2.0}), std::invalid_argument);
}

// A time-optimal path that reaches a's upper limit and runs along it while b moves, at move_group's 0.1 s between
// points: the quintic over the interval where the blend arc meets the straight segment along the limit (a's
// acceleration jumps from braking to 0 inside it) passes the limit, though every point is within it. Bounded by the
// limits, the samples stay within them and still pass through every point.
TEST(Trajectory, BoundedSamplingOfAPathAlongALimitStaysWithinIt) {
  const double upper = 1.0;
  TimeParameterizationOptions o;
  o.max_velocity = {2.0, 1.7};
  o.max_acceleration = {4.0, 4.0};
  o.acceleration_scaling = 0.5;
  o.sample_period = 0.1;
  const auto r = computeTimeOptimalTrajectory({"a", "b"}, {{upper - 0.025, 0}, {upper, 0.08}, {upper, 0.35}}, o);
  ASSERT_TRUE(r.ok()) << r.message;
  for (const TrajectoryPoint& p : r.trajectory.points) ASSERT_LE(p.positions[0], upper);
  const TrajectorySampler unbounded(r.trajectory);
  const TrajectorySampler bounded(r.trajectory, {-upper, -upper}, {upper, upper});
  double overshoot = 0.0;
  for (double time = 0.0; time <= r.trajectory.duration(); time += 2.5e-4) {
    overshoot = std::max(overshoot, unbounded.sample(time).position[0] - upper);
    ASSERT_LE(bounded.sample(time).position[0], upper) << "t=" << time;
  }
  EXPECT_GT(overshoot, 1e-5) << "the path no longer reproduces the quintic's overshoot";
  for (const TrajectoryPoint& p : r.trajectory.points) {
    EXPECT_EQ(bounded.sample(p.time_from_start).position, p.positions);
  }
}

TEST(JointSpline, EndpointConditionsHoldForEveryType) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 100; ++trial) {
    const double t = 0.1 + std::abs(u(rng));
    const double p0 = u(rng), v0 = u(rng), a0 = u(rng), p1 = u(rng), v1 = u(rng), a1 = u(rng);
    double p, v, a;

    JointSpline quintic(InterpolationType::kQuintic, t, p0, v0, a0, p1, v1, a1);
    quintic.sample(0.0, p, v, a);
    EXPECT_NEAR(p, p0, 1e-9);
    EXPECT_NEAR(v, v0, 1e-9);
    EXPECT_NEAR(a, a0, 1e-9);
    quintic.sample(t, p, v, a);
    EXPECT_NEAR(p, p1, 1e-9);
    EXPECT_NEAR(v, v1, 1e-8);
    EXPECT_NEAR(a, a1, 1e-7);

    JointSpline cubic(InterpolationType::kCubic, t, p0, v0, 0.0, p1, v1, 0.0);
    cubic.sample(0.0, p, v, a);
    EXPECT_NEAR(p, p0, 1e-9);
    EXPECT_NEAR(v, v0, 1e-9);
    cubic.sample(t, p, v, a);
    EXPECT_NEAR(p, p1, 1e-9);
    EXPECT_NEAR(v, v1, 1e-8);

    JointSpline linear(InterpolationType::kLinear, t, p0, 0.0, 0.0, p1, 0.0, 0.0);
    linear.sample(0.5 * t, p, v, a);
    EXPECT_NEAR(p, 0.5 * (p0 + p1), 1e-9);
    EXPECT_NEAR(v, (p1 - p0) / t, 1e-9);
    EXPECT_NEAR(a, 0.0, 1e-12);
  }
}

TEST(JointSpline, DerivativesMatchFiniteDifferences) {
  JointSpline s(InterpolationType::kQuintic, 2.0, 0.3, -0.5, 1.0, 1.2, 0.4, -0.7);
  const double h = 1e-6;
  for (double t = 0.1; t < 1.9; t += 0.17) {
    double p0, v0, a0, p1, v1, a1, p, v, a;
    s.sample(t - h, p0, v0, a0);
    s.sample(t + h, p1, v1, a1);
    s.sample(t, p, v, a);
    EXPECT_NEAR(v, (p1 - p0) / (2 * h), 1e-6);
    EXPECT_NEAR(a, (v1 - v0) / (2 * h), 1e-5);
  }
}

TEST(JointSpline, ClampsOutsideItsSpan) {
  JointSpline s(InterpolationType::kCubic, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0);
  double p, v, a;
  s.sample(5.0, p, v, a);
  EXPECT_DOUBLE_EQ(p, 1.0);
  s.sample(-1.0, p, v, a);
  EXPECT_DOUBLE_EQ(p, 0.0);
  EXPECT_THROW(JointSpline(InterpolationType::kLinear, 0.0, 0, 0, 0, 1, 0, 0), std::invalid_argument);
}

TEST(InterpolationType, IsTheHighestOrderBothPointsCarry) {
  TrajectoryPoint pos{{1.0}, {}, {}, 0.0};
  TrajectoryPoint vel{{1.0}, {0.0}, {}, 0.0};
  TrajectoryPoint acc{{1.0}, {0.0}, {0.0}, 0.0};
  EXPECT_EQ(interpolationType(pos, acc), InterpolationType::kLinear);
  EXPECT_EQ(interpolationType(acc, vel), InterpolationType::kCubic);
  EXPECT_EQ(interpolationType(vel, vel), InterpolationType::kCubic);
  EXPECT_EQ(interpolationType(acc, acc), InterpolationType::kQuintic);
}

TEST(Trajectory, SamplingATimeParameterizedTrajectoryStaysWithinLimits) {
  TimeParameterizationOptions o;
  o.max_velocity = {1.0, 2.0};
  o.max_acceleration = {2.0, 3.0};
  o.sample_period = 0.05;  // coarse points; sampling fills the gaps
  const auto r = computeTimeOptimalTrajectory({"a", "b"}, {{0, 0}, {1, 0.5}, {0.2, 1.5}, {1.0, 1.0}}, o);
  ASSERT_TRUE(r.ok()) << r.message;
  const TrajectorySampler t(r.trajectory);
  for (const TrajectoryPoint& p : t.trajectory().points) {
    EXPECT_EQ(t.sample(p.time_from_start).position, p.positions);
  }
  // Between points the quintic may overshoot the bang-bang profile a little; 2% bounds it here.
  for (double time = 0.0; time <= t.endTime(); time += 0.001) {
    const TrajectorySample s = t.sample(time);
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_LE(std::abs(s.velocity[j]), o.max_velocity[j] * 1.02) << "t=" << time;
    }
  }
}

}  // namespace
}  // namespace sixdof_core
