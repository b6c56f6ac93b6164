#pragma once
// The planning benchmarks' query chain on the table-top world (plan_bench, scaling_bench): pose queries (pre-grasp
// above the cube, pre-place, and random top-down poses over the table), each planned from where the previous one
// ended, and their statistics.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "../test/test_planning_table_top.h"
#include "bench_paths.h"
#include "sixdof_core/planning_context.h"

namespace sixdof_core::bench {

// The arguments of the planning benchmarks: `name [queries (default 100)] [urdf] [srdf]`, the robot defaulting to the
// checkout's description. False (after a usage line) on a bad count; true with OMPL's log quieted to errors (the
// benchmarks print their tables only).
struct QueryArgs {
  int queries = 100;
  std::string description, urdf, srdf;

  bool parse(int argc, char** argv, const char* name) {
    queries = argc > 1 ? std::atoi(argv[1]) : 100;
    description = descriptionDir();
    urdf = argc > 2 ? argv[2] : defaultUrdf();
    srdf = argc > 3 ? argv[3] : defaultSrdf();
    if (queries >= 1) {
      ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
      return true;
    }
    std::fprintf(stderr, "usage: %s [queries >= 1] [urdf] [srdf]\n", name);
    return false;
  }
};

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5));
  return v[i];
}

inline double median(const std::vector<double>& v) { return percentile(v, 0.5); }

struct Run {
  std::vector<double> times;           // s, every query
  std::vector<double> simplify_times;  // s, solved queries
  std::vector<double> lengths;         // joint-space path length, solved queries
  int solved = 0;
  int fallbacks = 0;
  std::size_t checks = 0;
  std::size_t precheck_calls = 0;
  std::size_t precheck_states = 0;
  std::vector<int> failures = std::vector<int>(8, 0);

  // Queries whose goal no collision-free IK solution reaches (counted apart from the planner's failures).
  int infeasible() const {
    return failures[static_cast<int>(PlanningStatus::kGoalInCollision)] +
           failures[static_cast<int>(PlanningStatus::kNoIkSolution)];
  }
};

// The chain of `queries` pose queries over the table (seeded: the same queries in every run).
inline Run runQueries(const sixdof_test::TableTop& t, int queries, PlanningOptions options) {
  using sixdof_test::TableTop;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> x(0.20, 0.50), y(-0.35, 0.35), z(0.08, 0.30), yaw(-1.0, 1.0);
  RobotState state(t.model);
  state.setGroupPositions("arm", Eigen::VectorXd::Zero(6));
  Run run;
  for (int q = 0; q < queries; ++q) {
    Eigen::Isometry3d tcp;
    if (q % 3 == 0) {
      tcp = TableTop::topDown(0.40, -0.15, 0.12, yaw(rng) * 0.3);
    } else if (q % 3 == 1) {
      tcp = TableTop::topDown(0.40, 0.20, 0.12, yaw(rng) * 0.3);
    } else {
      tcp = TableTop::topDown(x(rng), y(rng), z(rng), yaw(rng));
    }
    options.seed = static_cast<std::uint32_t>(q + 1);
    const PlanningResult r = t.context->planToPose(state, t.tipFor(tcp), PoseGoalOptions(), options);
    run.times.push_back(r.planning_time);
    run.checks += r.validity_checks;
    run.precheck_calls += r.precheck_calls;
    run.precheck_states += r.precheck_states;
    if (r.ok()) {
      ++run.solved;
      run.simplify_times.push_back(r.simplification_time);
      run.lengths.push_back(r.path_length);
      run.fallbacks += r.simplification_fallback;
      state.setGroupPositions("arm", r.path.back());
    } else {
      ++run.failures[static_cast<int>(r.status)];
    }
  }
  return run;
}

}  // namespace sixdof_core::bench
