// How cost grows with the number of obstacles: the table-top world plus N boxes of clutter (1.5-3 cm, resting on the
// table at seeded random places and yaws, none within 8 cm of the cube, the place location, the post, the ball or
// the robot's base), for N = 10, 100, 1000:
//  - planning: plan_bench's query chain (RRTConnect, 1 s allowed, motions checked every 0.005 rad), success and
//    planning time with the sphere pre-check and, in the same run, without it (every motion state by FCL);
//  - collision checks per second on random arm states: full-state checks (forward kinematics + FCL, what the planner's
//    validity callback does) and pre-check calls (forward kinematics + spheres, over a 0.05 rad step).
//   scaling_bench [queries per scene (default 100)] [urdf] [srdf]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "plan_queries.h"

namespace {

using sixdof_core::bench::median;
using sixdof_core::bench::percentile;
using sixdof_core::bench::Run;
using sixdof_core::bench::runQueries;

constexpr int kObstacleCounts[] = {10, 100, 1000};

std::vector<sixdof_core::WorldObject> clutter(int count) {
  const std::vector<Eigen::Vector2d> keep_out = {{0.40, -0.15}, {0.40, 0.20}, {0.42, 0.03}, {0.20, 0.30}, {0.0, 0.0}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-0.28, 0.88), y(-0.58, 0.58), size(0.015, 0.03), yaw(-M_PI, M_PI);
  std::vector<sixdof_core::WorldObject> objects;
  while (static_cast<int>(objects.size()) < count) {
    const Eigen::Vector2d at(x(rng), y(rng));
    bool free = (at - keep_out.back()).norm() > 0.20;  // the base
    for (std::size_t k = 0; k + 1 < keep_out.size(); ++k) free = free && (at - keep_out[k]).norm() > 0.08;
    if (!free) continue;
    const double side = size(rng);
    sixdof_core::WorldObject o =
        sixdof_test::tableTopObject("clutter_" + std::to_string(objects.size()), sixdof_core::Shape::Type::kBox,
                                    {at.x(), at.y(), side / 2.0}, {side, side, side});
    o.pose.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    objects.push_back(o);
  }
  return objects;
}

template <typename F>
double perSecond(int calls, F&& call) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < calls; ++i) call(i);
  return calls / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  sixdof_core::bench::QueryArgs args;
  if (!args.parse(argc, argv, "scaling_bench")) return 2;
  const int queries = args.queries;
  std::printf(
      "scaling_bench: the table-top world plus N boxes of clutter on the table, %d chained pose queries per "
      "scene (plan_bench's), 4096 random arm states for the checks\n",
      queries);

  sixdof_core::PlanningOptions options;
  options.allowed_planning_time = 1.0;
  options.longest_valid_segment_length = 0.005;
  options.max_joint_step = 0.05;
  std::vector<std::string> planning_rows, check_rows;
  for (const int count : kObstacleCounts) {
    const sixdof_test::TableTop t =
        sixdof_test::makeTableTop(args.urdf, args.srdf, args.description, 0.005, clutter(count));
    options.precheck = true;
    const Run ours = runQueries(t, queries, options);
    options.precheck = false;
    const Run exact = runQueries(t, queries, options);
    const int feasible = queries - ours.infeasible();
    char row[256];
    std::snprintf(row, sizeof(row), "| %d | %d | %d | %.2f | %.2f | %d | %.2f | %.2f |", count, feasible, ours.solved,
                  1e3 * median(ours.times), 1e3 * percentile(ours.times, 0.95), exact.solved, 1e3 * median(exact.times),
                  1e3 * percentile(exact.times, 0.95));
    planning_rows.push_back(row);

    std::mt19937 rng(42);
    std::vector<Eigen::VectorXd> states, steps;
    for (int i = 0; i < 4096; ++i) {
      Eigen::VectorXd q(6), step(6);
      for (int j = 0; j < 6; ++j) {
        const sixdof_core::JointBounds& b = t.context->joints()[j];
        q[j] = std::uniform_real_distribution<double>(b.lower, b.upper)(rng);
        step[j] = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
      }
      states.push_back(q);
      steps.push_back(step.normalized() * 0.05);
    }
    const sixdof_core::RobotState reference(t.model);
    const sixdof_core::JointValidityFn valid = t.context->validityFn(reference);
    const sixdof_core::MotionPrecheckFn precheck = t.context->precheckFn(reference);
    volatile double sink = 0.0;
    const double fcl_rate = perSecond(4 * 4096, [&](int i) { sink = sink + valid(states[i & 4095]); });
    const double precheck_rate =
        perSecond(4 * 4096, [&](int i) { sink = sink + precheck(states[i & 4095], steps[i & 4095], 1.0, 0.1).proven; });
    std::snprintf(row, sizeof(row), "| %d | %.0f | %.0f |", count, fcl_rate, precheck_rate);
    check_rows.push_back(row);
  }
  std::printf("\nplanning time vs obstacles (RRTConnect, 0.005 rad)\n\n");
  std::printf(
      "| boxes | feasible | solved, pre-check | median ms, pre-check | p95 ms, pre-check | solved, FCL only | "
      "median ms, FCL only | p95 ms, FCL only |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& row : planning_rows) std::printf("%s\n", row.c_str());
  std::printf("\ncollision checks per second vs obstacles (random arm states)\n\n");
  std::printf("| boxes | full-state checks/s (FK + FCL) | pre-check calls/s (FK + spheres) |\n|---:|---:|---:|\n");
  for (const std::string& row : check_rows) std::printf("%s\n", row.c_str());
  return 0;
}
