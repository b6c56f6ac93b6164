// Planning benchmark on the table-top pick-and-place world: a chain of pose queries (pre-grasp above the cube,
// pre-place, and random top-down poses over the table), each planned from where the previous one ended with
// RRTConnect (1 s allowed), IK-sampled goals, simplification. Reports success within 1 s over the feasible
// queries (random poses whose every IK solution collides, or that IK cannot reach, are counted apart), median
// and p95 planning time, path length, and validity (collision) checks per second of planning; then the same
// queries with the baseline simplification (every shortcut checked at the planning resolution).
//   plan_bench [queries (default 100)] [urdf] [srdf]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "../test/test_planning_table_top.h"
#include "bench_paths.h"
#include "sixdof_core/planning_context.h"

namespace {

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5));
  return v[i];
}

double median(const std::vector<double>& v) { return v.empty() ? 0.0 : percentile(v, 0.5); }

struct Run {
  std::vector<double> times;          // s, every query
  std::vector<double> simplify_times;  // s, solved queries
  std::vector<double> lengths;        // joint-space path length, solved queries
  int solved = 0;
  int fallbacks = 0;
  std::size_t checks = 0;
  std::vector<int> failures = std::vector<int>(8, 0);
};

// A chain of pose queries over the table, each planned from where the previous one ended.
Run runQueries(const sixdof_test::TableTop& t, int queries, sixdof_core::PlanningOptions options) {
  using sixdof_test::TableTop;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> x(0.20, 0.50), y(-0.35, 0.35), z(0.08, 0.30), yaw(-1.0, 1.0);
  sixdof_core::RobotState state(t.model);
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
    const sixdof_core::PlanningResult r =
        t.context->planToPose(state, t.tipFor(tcp), sixdof_core::PoseGoalOptions(), options);
    run.times.push_back(r.planning_time);
    run.checks += r.validity_checks;
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

void print(const char* title, const Run& run) {
  using sixdof_core::PlanningStatus;
  const int queries = static_cast<int>(run.times.size());
  const int infeasible = run.failures[static_cast<int>(PlanningStatus::kGoalInCollision)] +
                         run.failures[static_cast<int>(PlanningStatus::kNoIkSolution)];
  const int feasible = queries - infeasible;
  double total_time = 0.0;
  for (double t : run.times) total_time += t;
  std::printf("\n%s\n", title);
  std::printf("  success within 1 s: %d/%d feasible queries (%.1f %%); %d infeasible goals\n", run.solved, feasible,
              feasible ? 100.0 * run.solved / feasible : 0.0, infeasible);
  for (std::size_t s = 0; s < run.failures.size(); ++s) {
    if (run.failures[s]) {
      std::printf("    %s: %d\n", sixdof_core::toString(static_cast<PlanningStatus>(s)), run.failures[s]);
    }
  }
  std::printf("  planning time: median %.1f ms, p95 %.1f ms, max %.1f ms (simplification: median %.1f ms)\n",
              1e3 * median(run.times), 1e3 * percentile(run.times, 0.95), 1e3 * percentile(run.times, 1.0),
              1e3 * median(run.simplify_times));
  std::printf("  path length (rad): median %.3f, p95 %.3f; coarse simplification failed its re-check (simplified again at full resolution): %d\n",
              median(run.lengths), run.lengths.empty() ? 0.0 : percentile(run.lengths, 0.95), run.fallbacks);
  std::printf("  validity checks: %zu, %.0f per second of planning\n", run.checks, run.checks / total_time);
}

}  // namespace

int main(int argc, char** argv) {
  const int queries = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::string description = sixdof_core::bench::descriptionDir();
  const std::string urdf = argc > 2 ? argv[2] : sixdof_core::bench::defaultUrdf();
  const std::string srdf = argc > 3 ? argv[3] : sixdof_core::bench::defaultSrdf();
  if (queries < 1) {
    std::fprintf(stderr, "usage: plan_bench [queries >= 1] [urdf] [srdf]\n");
    return 2;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  const sixdof_test::TableTop t = sixdof_test::makeTableTop(urdf, srdf, description, 0.005);
  std::printf("plan_bench: %s + %s, IK %s, %d queries\n", urdf.c_str(), srdf.c_str(), t.ik_note.c_str(), queries);

  sixdof_core::PlanningOptions options;
  options.allowed_planning_time = 1.0;
  options.longest_valid_segment_length = 0.005;
  options.max_joint_step = 0.05;
  const Run ours = runQueries(t, queries, options);
  print("default: simplification checked 4x coarser, then re-checked at the planning resolution", ours);
  // Baseline, same queries in the same run: OMPL's simplifier checking every shortcut at the planning
  // resolution (as MoveIt does).
  options.simplify_coarse_factor = 1.0;
  const Run baseline = runQueries(t, queries, options);
  print("baseline: simplification at the planning resolution", baseline);
  std::printf("median planning time: baseline / default = %.2f\n", median(baseline.times) / median(ours.times));
  std::printf("median path length: default / baseline = %.3f\n", median(ours.lengths) / median(baseline.lengths));
  // move_group's default resolution (MoveIt's): 0.005 of the joint space's maximum extent, about 17x coarser
  // here; the coarse simplification pass is then off (it never checks coarser than that).
  options.simplify_coarse_factor = sixdof_core::PlanningOptions().simplify_coarse_factor;
  options.longest_valid_segment_length = 0.0;
  options.longest_valid_segment_fraction = 0.005;
  print("move_group's default resolution: longest_valid_segment_fraction 0.005", runQueries(t, queries, options));
  return 0;
}
