// Time parameterization benchmark: computeTimeOptimalTrajectory on paths like the planner's (3 to 6 waypoints,
// uniformly random within the joint ranges of the model's first group, fixed seed), at velocity scaling 0.1 and
// 1.0 with the default path resolution (1e-2 rad) and sample period (10 ms), and at 1.0 with move_group's sample
// period (its trajectory_sample_period, 0.1 s: fewer output points). Velocity limits come from the URDF;
// acceleration limits are twice the velocity limits (the URDF has none). Reports the median and p95 time per call
// over every path, repeated, and a hash of every output value's bits (equal hashes: identical outputs).
//   retime_bench [paths (default 50)] [repeats (default 20)] [urdf] [srdf]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench_paths.h"
#include "sixdof_core/robot_model.h"
#include "sixdof_core/time_parameterization.h"

namespace {

using sixdof_core::TimeParameterizationOptions;

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

// FNV-1a over the bytes of every double of the trajectory.
void hashValues(const std::vector<double>& values, std::uint64_t* hash) {
  for (double v : values) {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &v, sizeof(double));
    for (unsigned char b : bytes) *hash = (*hash ^ b) * 1099511628211ULL;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int paths = argc > 1 ? std::atoi(argv[1]) : 50;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
  const std::string urdf = argc > 3 ? argv[3] : sixdof_core::bench::defaultUrdf();
  // The report names the default arm by its package, not by the folder of this checkout.
  const std::string urdf_name = argc > 3 ? argv[3] : "package://sixdof_description/urdf/sixdof.urdf";
  const std::string srdf = argc > 4 ? argv[4] : sixdof_core::bench::defaultSrdf();
  if (paths < 1 || repeats < 1) {
    std::fprintf(stderr, "retime_bench: paths and repeats must be >= 1\n");
    return 2;
  }
  const auto model = sixdof_core::RobotModel::fromFiles(
      urdf, srdf,
      sixdof_core::PackageResolver::fromMap({{"sixdof_description", sixdof_core::bench::descriptionDir()}}));
  if (model->groups().empty()) {
    std::fprintf(stderr, "retime_bench: %s declares no group\n", srdf.c_str());
    return 2;
  }
  const sixdof_core::JointGroup& group = model->groups().front();
  TimeParameterizationOptions options;
  for (const std::string& name : group.active_joints) {
    const double v = model->joint(name).limits.velocity;
    options.max_velocity.push_back(v);
    options.max_acceleration.push_back(2.0 * v);
  }
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> count(3, 6);
  std::vector<std::vector<std::vector<double>>> waypoints(paths);
  for (auto& path : waypoints) {
    path.resize(count(rng));
    for (auto& w : path) {
      for (const std::string& name : group.active_joints) {
        const auto& limits = model->joint(name).limits;
        w.push_back(std::uniform_real_distribution<double>(limits.lower, limits.upper)(rng));
      }
    }
  }
  std::printf("retime_bench: group %s of %s, %d paths of 3-6 waypoints, %d calls each\n\n", group.name.c_str(),
              urdf_name.c_str(), paths, repeats);
  std::printf("| velocity scaling | sample period (s) | median (ms) | p95 (ms) | output points (median) | output hash "
              "|\n");
  std::printf("|---|---|---|---|---|---|\n");
  const double default_period = options.sample_period;
  const std::vector<std::pair<double, double>> cases{{0.1, default_period}, {1.0, default_period}, {1.0, 0.1}};
  for (const auto& [scaling, period] : cases) {
    options.velocity_scaling = scaling;
    options.sample_period = period;
    std::vector<double> times, sizes;
    std::uint64_t hash = 1469598103934665603ULL;
    for (const auto& path : waypoints) {
      for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const auto result = sixdof_core::computeTimeOptimalTrajectory(group.active_joints, path, options);
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!result.ok()) {
          std::fprintf(stderr, "retime_bench: %s\n", result.message.c_str());
          return 1;
        }
        if (r > 0) continue;
        sizes.push_back(static_cast<double>(result.trajectory.points.size()));
        for (const auto& p : result.trajectory.points) {
          hashValues({p.time_from_start}, &hash);
          hashValues(p.positions, &hash);
          hashValues(p.velocities, &hash);
          hashValues(p.accelerations, &hash);
        }
      }
    }
    std::printf("| %.1f | %g | %.3f | %.3f | %.0f | %016llx |\n", scaling, period, 1e3 * percentile(times, 0.5),
                1e3 * percentile(times, 0.95), percentile(sizes, 0.5), static_cast<unsigned long long>(hash));
  }
  return 0;
}
