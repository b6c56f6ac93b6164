// Iterative parabolic parameterization: one point per waypoint, at rest at both ends, every segment's velocity and
// acceleration within the scaled limits, slower for smaller scaling factors; bad input and a single point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sixdof_core/time_parameterization.h"

namespace sixdof_core {
namespace {

const std::vector<std::string> kJoints = {"a", "b", "c"};

TimeParameterizationOptions limits(double scaling) {
  TimeParameterizationOptions o;
  o.max_velocity = {1.0, 0.5, 2.0};
  o.max_acceleration = {2.0, 1.0, 0.5};
  o.velocity_scaling = o.acceleration_scaling = scaling;
  return o;
}

// A random walk of 30 points, steps up to 0.2 rad per joint.
std::vector<std::vector<double>> randomWalk(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(-0.2, 0.2);
  std::vector<std::vector<double>> path(1, std::vector<double>(kJoints.size(), 0.0));
  for (int i = 1; i < 30; ++i) {
    path.push_back(path.back());
    for (double& v : path.back()) v += step(rng);
  }
  return path;
}

TEST(IterativeParabolic, KeepsEveryWaypointWithinTheScaledLimits) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const auto path = randomWalk(seed);
    const TimeParameterizationOptions o = limits(0.5);
    const auto result = computeIterativeParabolicTrajectory(kJoints, path, o);
    ASSERT_TRUE(result.ok()) << result.message;
    const Trajectory& t = result.trajectory;
    ASSERT_EQ(validateTrajectory(t), "");
    ASSERT_EQ(t.points.size(), path.size());
    EXPECT_EQ(t.points.front().time_from_start, 0.0);
    for (std::size_t j = 0; j < kJoints.size(); ++j) {
      EXPECT_EQ(t.points.front().velocities[j], 0.0);
      EXPECT_EQ(t.points.back().velocities[j], 0.0);
    }
    for (std::size_t i = 0; i < path.size(); ++i) {
      EXPECT_EQ(t.points[i].positions, path[i]);
      if (i == 0) continue;
      const double dt = t.points[i].time_from_start - t.points[i - 1].time_from_start;
      ASSERT_GT(dt, 0.0);
      for (std::size_t j = 0; j < kJoints.size(); ++j) {
        const double vmax = o.max_velocity[j] * o.velocity_scaling;
        const double amax = o.max_acceleration[j] * o.acceleration_scaling;
        EXPECT_LE(std::abs(path[i][j] - path[i - 1][j]) / dt, vmax * (1 + 1e-9));
        EXPECT_LE(std::abs(t.points[i].velocities[j]), vmax * (1 + 1e-9));
        EXPECT_LE(std::abs(t.points[i].velocities[j] - t.points[i - 1].velocities[j]) / dt, amax * (1 + 1e-6));
      }
    }
    const auto faster = computeIterativeParabolicTrajectory(kJoints, path, limits(1.0));
    ASSERT_TRUE(faster.ok());
    EXPECT_LT(faster.trajectory.duration(), t.duration());
  }
}

TEST(IterativeParabolic, SinglePointIsAtRestAndBadInputIsNamed) {
  const auto single = computeIterativeParabolicTrajectory(kJoints, {{0.1, 0.2, 0.3}}, limits(1.0));
  ASSERT_TRUE(single.ok()) << single.message;
  ASSERT_EQ(single.trajectory.points.size(), 1u);
  EXPECT_EQ(single.trajectory.points[0].time_from_start, 0.0);
  EXPECT_EQ(single.trajectory.points[0].velocities, std::vector<double>(3, 0.0));
  EXPECT_EQ(single.trajectory.points[0].accelerations, std::vector<double>(3, 0.0));
  TimeParameterizationOptions bad = limits(1.0);
  bad.max_acceleration[1] = 0.0;
  const auto refused = computeIterativeParabolicTrajectory(kJoints, randomWalk(1), bad);
  EXPECT_EQ(refused.status, TimeParameterizationStatus::kInvalidInput);
  EXPECT_NE(refused.message.find("max_acceleration of b"), std::string::npos) << refused.message;
  const auto scaled = computeIterativeParabolicTrajectory(kJoints, randomWalk(1), limits(1.5));
  EXPECT_EQ(scaled.status, TimeParameterizationStatus::kInvalidInput);
}

}  // namespace
}  // namespace sixdof_core
