// Trajectory validation and sampling (the interpolation a joint_trajectory_controller applies).
#include <gtest/gtest.h>

#include <cmath>

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
  Trajectory quintic;
  quintic.joint_names = {"j"};
  quintic.points = {point(0.5, {q(0.5)}, {v(0.5)}, {a(0.5)}), point(2.0, {q(2.0)}, {v(2.0)}, {a(2.0)})};
  for (double t : {0.5, 0.9, 1.3, 1.77, 2.0}) {
    const TrajectorySample s = sampleTrajectory(quintic, t);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_NEAR(s.point.positions[0], q(t), 1e-9);
    EXPECT_NEAR(s.point.velocities[0], v(t), 1e-9);
    EXPECT_NEAR(s.point.accelerations[0], a(t), 1e-9);
    EXPECT_DOUBLE_EQ(s.point.time_from_start, t);
  }
  // Before the first point's time the first point holds, at rest.
  const TrajectorySample before = sampleTrajectory(quintic, 0.2);
  ASSERT_TRUE(before.ok);
  EXPECT_DOUBLE_EQ(before.point.positions[0], q(0.5));
  EXPECT_DOUBLE_EQ(before.point.velocities[0], 0.0);

  // Cubic with velocities only: q = t^3 - t on [0, 1].
  Trajectory cubic;
  cubic.joint_names = {"j"};
  cubic.points = {point(0.0, {0.0}, {-1.0}), point(1.0, {0.0}, {2.0})};
  const TrajectorySample c = sampleTrajectory(cubic, 0.5);
  ASSERT_TRUE(c.ok);
  EXPECT_NEAR(c.point.positions[0], 0.125 - 0.5, 1e-12);
  EXPECT_NEAR(c.point.velocities[0], 0.75 - 1.0, 1e-12);
  EXPECT_NEAR(c.point.accelerations[0], 3.0, 1e-12);

  // Linear with positions only.
  Trajectory linear;
  linear.joint_names = {"a", "b"};
  linear.points = {point(0.0, {0.0, 1.0}), point(2.0, {1.0, -1.0})};
  const TrajectorySample l = sampleTrajectory(linear, 0.5);
  ASSERT_TRUE(l.ok);
  EXPECT_NEAR(l.point.positions[0], 0.25, 1e-12);
  EXPECT_NEAR(l.point.positions[1], 0.5, 1e-12);
  EXPECT_NEAR(l.point.velocities[1], -1.0, 1e-12);
}

TEST(Trajectory, SamplingRejectsBadTimesAndTrajectories) {
  Trajectory t;
  t.joint_names = {"j"};
  t.points = {point(0.0, {0.0}), point(1.0, {1.0})};
  for (double time : {-0.1, 1.01, static_cast<double>(NAN)}) {
    const TrajectorySample s = sampleTrajectory(t, time);
    EXPECT_FALSE(s.ok);
    EXPECT_NE(s.message.find("outside [0, 1]"), std::string::npos) << s.message;
  }
  EXPECT_TRUE(sampleTrajectory(t, 1.0).ok);
  Trajectory empty;
  empty.joint_names = {"j"};
  EXPECT_EQ(sampleTrajectory(empty, 0.0).message, "trajectory has no points");
}

TEST(Trajectory, SamplingATimeParameterizedTrajectoryStaysWithinLimits) {
  TimeParameterizationOptions o;
  o.max_velocity = {1.0, 2.0};
  o.max_acceleration = {2.0, 3.0};
  o.sample_period = 0.05;  // coarse points; sampling fills the gaps
  const auto r = computeTimeOptimalTrajectory({"a", "b"}, {{0, 0}, {1, 0.5}, {0.2, 1.5}, {1.0, 1.0}}, o);
  ASSERT_TRUE(r.ok()) << r.message;
  const Trajectory& t = r.trajectory;
  for (const TrajectoryPoint& p : t.points) {
    const TrajectorySample s = sampleTrajectory(t, p.time_from_start);
    ASSERT_TRUE(s.ok);
    EXPECT_EQ(s.point.positions, p.positions);
  }
  // Between points the quintic may overshoot the bang-bang profile a little; 2% bounds it here.
  for (double time = 0.0; time <= t.duration(); time += 0.001) {
    const TrajectorySample s = sampleTrajectory(t, time);
    ASSERT_TRUE(s.ok);
    for (std::size_t j = 0; j < 2; ++j) {
      EXPECT_LE(std::abs(s.point.velocities[j]), o.max_velocity[j] * 1.02) << "t=" << time;
    }
  }
}

}  // namespace
}  // namespace sixdof_core
