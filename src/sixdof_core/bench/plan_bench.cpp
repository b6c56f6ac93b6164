// Planning benchmark on the table-top pick-and-place world: a chain of pose queries (pre-grasp above the cube,
// pre-place, and random top-down poses over the table), each planned from where the previous one ended with
// RRTConnect (1 s allowed), IK-sampled goals, simplification. Reports success within 1 s over the feasible
// queries (random poses whose every IK solution collides, or that IK cannot reach, are counted apart), median
// and p95 planning time, path length, and validity (collision) checks per second of planning; then the same
// queries without the motion pre-check, with the simplification's coarse pass, and at move_group's resolution.
//   plan_bench [queries (default 100)] [urdf] [srdf]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plan_queries.h"

namespace {

using sixdof_core::bench::median;
using sixdof_core::bench::percentile;
using sixdof_core::bench::Run;
using sixdof_core::bench::runQueries;

void print(const char* title, const Run& run) {
  using sixdof_core::PlanningStatus;
  const int queries = static_cast<int>(run.times.size());
  const int infeasible = run.infeasible();
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
  if (run.precheck_calls) {
    std::printf("  pre-check: %zu calls proved %zu motion states valid without a validity check\n", run.precheck_calls,
                run.precheck_states);
  }
}

}  // namespace

int main(int argc, char** argv) {
  sixdof_core::bench::QueryArgs args;
  if (!args.parse(argc, argv, "plan_bench")) return 2;
  const int queries = args.queries;
  const sixdof_test::TableTop t = sixdof_test::makeTableTop(args.urdf, args.srdf, args.description, 0.005);
  std::printf("plan_bench: %s + %s, IK %s, %d queries\n", args.urdf.c_str(), args.srdf.c_str(), t.ik_note.c_str(),
              queries);

  sixdof_core::PlanningOptions options;
  options.allowed_planning_time = 1.0;
  options.longest_valid_segment_length = 0.005;
  options.max_joint_step = 0.05;
  const Run ours = runQueries(t, queries, options);
  print("default: sphere pre-check of motions; simplification (up to 3 rounds of OMPL's vertex reduction, then up to 5 "
        "of shortcutting; no better-goal search or B-spline smoothing, unlike MoveIt's simplifySolution) checked at the "
        "planning resolution",
        ours);
  // Baseline, same queries in the same run: every motion state checked with FCL (no pre-check).
  options.precheck = false;
  const Run exact = runQueries(t, queries, options);
  print("baseline: no pre-check (every motion state checked with FCL)", exact);
  std::printf("median planning time: baseline / default = %.2f; p95: %.2f\n", median(exact.times) / median(ours.times),
              percentile(exact.times, 0.95) / percentile(ours.times, 0.95));
  options.precheck = true;
  // The alternative, same queries: the simplifier's shortcuts checked 4x coarser first (simplify_coarse_factor).
  options.simplify_coarse_factor = 4.0;
  const Run coarse = runQueries(t, queries, options);
  print("alternative: simplification checked 4x coarser first, then re-checked at the planning resolution (with the "
        "pre-check)",
        coarse);
  std::printf("planning time: coarse / default = %.2f at the median, %.2f at p95\n",
              median(coarse.times) / median(ours.times), percentile(coarse.times, 0.95) / percentile(ours.times, 0.95));
  std::printf("median path length: coarse / default = %.3f\n", median(coarse.lengths) / median(ours.lengths));
  // move_group's default resolution (MoveIt's): 0.005 of the joint space's maximum extent, about 17x coarser
  // here.
  options.simplify_coarse_factor = sixdof_core::PlanningOptions().simplify_coarse_factor;
  options.longest_valid_segment_length = 0.0;
  options.longest_valid_segment_fraction = 0.005;
  print("move_group's default resolution: longest_valid_segment_fraction 0.005", runQueries(t, queries, options));
  return 0;
}
