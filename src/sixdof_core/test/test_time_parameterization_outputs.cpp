// Time-optimal parameterization against stored outputs: random paths (sparse and dense, blends of every size)
// give the same point count and, within 1e-9, the same times and positions as the outputs stored in
// test/data/time_parameterization_outputs.txt, so that a change to the solver's arithmetic that is meant to
// change nothing but rounding is checked to do so. SIXDOF_WRITE_TIME_PARAMETERIZATION_OUTPUTS=1 writes that
// file from the current code instead (and fails, so that a run writing it never counts as a pass).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <random>
#include <string>
#include <vector>

#include "sixdof_core/time_parameterization.h"

namespace sixdof_core {
namespace {

const std::string kOutputsFile = std::string(SIXDOF_TEST_DATA_DIR) + "/time_parameterization_outputs.txt";
const std::vector<std::string> kJoints = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"};
constexpr int kPaths = 60;

struct Case {
  std::vector<std::vector<double>> waypoints;
  TimeParameterizationOptions options;
};

// Even cases: a few waypoints anywhere; odd cases: many waypoints a small step apart, like a planner's output.
Case randomCase(std::mt19937* rng, int index) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Case c;
  c.options.max_velocity = {2.0, 2.0, 2.0, 3.0, 3.0, 3.0};
  c.options.max_acceleration = {3.0, 2.5, 4.0, 6.0, 5.0, 8.0};
  c.options.velocity_scaling = 0.3 + 0.7 * unit(*rng);
  c.options.acceleration_scaling = 0.3 + 0.7 * unit(*rng);
  c.options.max_deviation = 0.3 * unit(*rng);
  c.options.sample_period = 0.5;
  const bool dense = index % 2 == 1;
  const int count = dense ? 8 + index % 9 : 2 + index % 7;
  std::vector<double> q(kJoints.size());
  for (double& v : q) v = 4.0 * unit(*rng) - 2.0;
  for (int w = 0; w < count; ++w) {
    c.waypoints.push_back(q);
    for (double& v : q) v += dense ? 0.3 * unit(*rng) - 0.1 : 4.0 * unit(*rng) - 2.0;
  }
  return c;
}

std::vector<Trajectory> currentOutputs() {
  std::mt19937 rng(2026);
  std::vector<Trajectory> outputs;
  for (int i = 0; i < kPaths; ++i) {
    const Case c = randomCase(&rng, i);
    TimeParameterizationResult r = computeTimeOptimalTrajectory(kJoints, c.waypoints, c.options);
    EXPECT_TRUE(r.ok()) << "path " << i << ": " << r.message;
    outputs.push_back(std::move(r.trajectory));
  }
  return outputs;
}

TEST(TimeParameterizationOutputs, SameAsStoredOutputs) {
  const std::vector<Trajectory> outputs = currentOutputs();
  if (std::getenv("SIXDOF_WRITE_TIME_PARAMETERIZATION_OUTPUTS") != nullptr) {
    std::ofstream out(kOutputsFile);
    out << std::setprecision(13);
    for (const Trajectory& t : outputs) {
      out << t.points.size() << '\n';
      for (const TrajectoryPoint& p : t.points) {
        out << p.time_from_start;
        for (double v : p.positions) out << ' ' << v;
        out << '\n';
      }
    }
    FAIL() << "wrote " << kOutputsFile << "; run again without SIXDOF_WRITE_TIME_PARAMETERIZATION_OUTPUTS to compare";
  }
  std::ifstream in(kOutputsFile);
  ASSERT_TRUE(in) << "cannot read " << kOutputsFile;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    std::size_t count = 0;
    ASSERT_TRUE(in >> count) << kOutputsFile << " ends before path " << i;
    ASSERT_EQ(outputs[i].points.size(), count) << "path " << i;
    for (std::size_t k = 0; k < count; ++k) {
      const TrajectoryPoint& p = outputs[i].points[k];
      double time = 0.0;
      ASSERT_TRUE(in >> time);
      EXPECT_NEAR(p.time_from_start, time, 1e-9) << "path " << i << " point " << k;
      for (std::size_t j = 0; j < kJoints.size(); ++j) {
        double position = 0.0;
        ASSERT_TRUE(in >> position);
        EXPECT_NEAR(p.positions[j], position, 1e-9) << "path " << i << " point " << k << " joint " << j;
      }
    }
  }
  std::size_t extra = 0;
  EXPECT_FALSE(in >> extra) << kOutputsFile << " holds more paths than " << kPaths;
}

}  // namespace
}  // namespace sixdof_core
