#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "sixdof_core/control/interpolation.h"

namespace sixdof_sim {
namespace {

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

TEST(JointTrajectory, SamplesKnotsSegmentsAndHoldsOutside) {
  JointTrajectory traj({1.0, 2.0, 4.0}, {{{0.0, 1.0}, {0.0, 0.0}, {}, 0.0},
                                         {{1.0, 0.0}, {0.5, 0.0}, {}, 1.0},
                                         {{2.0, -1.0}, {0.0, 0.0}, {}, 3.0}});
  EXPECT_EQ(traj.dof(), 2u);
  EXPECT_EQ(traj.segmentCount(), 2u);
  EXPECT_EQ(traj.segmentType(0), InterpolationType::kCubic);
  EXPECT_DOUBLE_EQ(traj.startTime(), 1.0);
  EXPECT_DOUBLE_EQ(traj.endTime(), 4.0);

  TrajectorySample k1 = traj.sample(2.0);
  EXPECT_NEAR(k1.position[0], 1.0, 1e-12);
  EXPECT_NEAR(k1.velocity[0], 0.5, 1e-12);
  EXPECT_NEAR(k1.position[1], 0.0, 1e-12);

  TrajectorySample before = traj.sample(0.0);
  EXPECT_EQ(before.position, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(before.velocity, (std::vector<double>{0.0, 0.0}));
  TrajectorySample after = traj.sample(10.0);
  EXPECT_EQ(after.position, (std::vector<double>{2.0, -1.0}));
  EXPECT_EQ(after.velocity, (std::vector<double>{0.0, 0.0}));

  // Inside a segment the sample lies between the knots for this monotone profile.
  TrajectorySample mid = traj.sample(3.0);
  EXPECT_GT(mid.position[0], 1.0);
  EXPECT_LT(mid.position[0], 2.0);
}

TEST(JointTrajectory, RejectsInconsistentKnots) {
  EXPECT_THROW(JointTrajectory({}, {}), std::invalid_argument);
  EXPECT_THROW(JointTrajectory({0.0, 0.0}, {{{0.0}, {}, {}, 0.0}, {{1.0}, {}, {}, 0.0}}), std::invalid_argument);
  EXPECT_THROW(JointTrajectory({0.0, 1.0}, {{{0.0}, {}, {}, 0.0}, {{1.0, 2.0}, {}, {}, 0.0}}),
               std::invalid_argument);
  EXPECT_THROW(JointTrajectory({0.0}, {{{0.0}, {1.0, 2.0}, {}, 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace sixdof_sim
