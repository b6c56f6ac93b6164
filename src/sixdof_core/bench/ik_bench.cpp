// IK benchmark: success rate and solve times of every solver on random reachable poses.
//   ik_bench [--urdf URDF] [--srdf SRDF] [--group arm] [--count 10000] [--timeout 0.005] [--seed 1]
//            [--solvers analytic,numeric,kdl,kdl_single]
// Defaults: the sixdof arm of this source tree (sixdof_description's URDF and SRDF; the core's test
// SRDF where the description has none). Mesh packages: sixdof_description from this tree, then
// ROS_PACKAGE_PATH.
// Poses are FK of uniformly random valid configurations (fixed seed); every solve starts from the
// middle of the joint ranges. A success counts only if the solution reproduces the pose to 1e-5.
// Prints a markdown table: wall-clock times (what a caller waits; the timeout is wall-clock too) and the
// thread's CPU time, which stays meaningful when other processes share the cores.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_paths.h"
#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/ik_kdl.h"
#include "sixdof_core/ik_numeric.h"
#include "sixdof_core/ik_solver.h"

using sixdof_core::IkOptions;
using sixdof_core::IkSolver;

namespace {

struct Row {
  std::string name;
  std::string note;
  double success_rate = 0.0;
  double median_us = 0.0;
  double p95_us = 0.0;
  double mean_us = 0.0;
  double cpu_median_us = 0.0;
  double cpu_mean_us = 0.0;
};

double threadCpuMicroseconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / values.size();
}

Row run(const std::string& name, const IkSolver& solver, const IkOptions& options,
        const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<double> times, cpu_times;
  times.reserve(poses.size());
  cpu_times.reserve(poses.size());
  int successes = 0;
  for (const auto& pose : poses) {
    const double cpu_start = threadCpuMicroseconds();
    const auto start = std::chrono::steady_clock::now();
    const sixdof_core::IkResult result = solver.solve(pose, options);
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
    cpu_times.push_back(threadCpuMicroseconds() - cpu_start);
    if (!result.ok()) continue;
    const sixdof_core::PoseError error = sixdof_core::poseError(solver.chain().forward(result.solution), pose);
    if (error.position < 1e-5 && (options.position_only || error.orientation < 1e-5)) ++successes;
  }
  Row row;
  row.name = name;
  row.success_rate = 100.0 * successes / poses.size();
  std::sort(times.begin(), times.end());
  row.median_us = times[times.size() / 2];
  row.p95_us = times[std::min(times.size() - 1, times.size() * 95 / 100)];
  row.mean_us = mean(times);
  std::sort(cpu_times.begin(), cpu_times.end());
  row.cpu_median_us = cpu_times[cpu_times.size() / 2];
  row.cpu_mean_us = mean(cpu_times);
  return row;
}

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "ik_bench: " << problem << "\n"
            << "usage: ik_bench [--urdf URDF] [--srdf SRDF] [--group arm] [--count 10000] [--timeout 0.005]\n"
            << "                [--seed 1] [--solvers analytic,numeric,kdl,kdl_single]\n";
  std::exit(2);
}

void parseArgument(const std::string& arg, const std::string& value, std::string* urdf, std::string* srdf,
                   std::string* group, std::string* solvers, int* count, double* timeout, unsigned long* seed) {
  if (arg == "--urdf") {
    *urdf = value;
  } else if (arg == "--srdf") {
    *srdf = value;
  } else if (arg == "--group") {
    *group = value;
  } else if (arg == "--count") {
    *count = std::stoi(value);
  } else if (arg == "--timeout") {
    *timeout = std::stod(value);
  } else if (arg == "--solvers") {
    *solvers = value;
  } else if (arg == "--seed") {
    *seed = std::stoul(value);
  } else {
    usage("unknown argument " + arg);
  }
}

int runBenchmark(const std::string& urdf, const std::string& srdf, const std::string& description,
                 const std::string& group, const std::string& solvers, int count, double timeout, unsigned long seed) {
  const char* ros_package_path = std::getenv("ROS_PACKAGE_PATH");
  auto resolver = sixdof_core::PackageResolver::fromRosPackagePath(ros_package_path ? ros_package_path : "");
  resolver.addPackage("sixdof_description", description);
  const auto model = sixdof_core::RobotModel::fromFiles(urdf, srdf, resolver);
  const sixdof_core::KinematicChain chain = sixdof_core::KinematicChain::forGroup(*model, group);

  std::mt19937_64 rng(seed);
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(count);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd q(chain.dof());
    for (size_t j = 0; j < chain.dof(); ++j) {
      q[j] = std::uniform_real_distribution<double>(chain.joint(j).limits.lower, chain.joint(j).limits.upper)(rng);
    }
    poses.push_back(chain.forward(q));
  }

  IkOptions options;
  options.timeout = timeout;
  IkOptions single;
  single.timeout = 0.0;
  single.attempts = 1;

  std::vector<Row> rows;
  std::stringstream names(solvers);
  for (std::string name; std::getline(names, name, ',');) {
    if (name == "analytic") {
      try {
        const sixdof_core::AnalyticIkSolver analytic(chain);
        rows.push_back(run("analytic", analytic, options, poses));
      } catch (const sixdof_core::AnalyticIkUnsupported& e) {
        Row row;
        row.name = "analytic";
        row.note = e.what();
        rows.push_back(row);
      }
    } else if (name == "numeric") {
      rows.push_back(run("numeric", sixdof_core::NumericIkSolver(chain), options, poses));
    } else if (name == "kdl") {
      rows.push_back(run("kdl", sixdof_core::KdlIkSolver(chain), options, poses));
    } else if (name == "kdl_single") {
      rows.push_back(run("KDL NR_JL, 1 attempt", sixdof_core::KdlIkSolver(chain), single, poses));
    } else {
      usage("unknown solver '" + name + "' in --solvers");
    }
  }

  std::printf("IK benchmark: %s, group '%s' (%s -> %s), %d random reachable poses, seed %lu, timeout %.1f ms\n\n",
              model->name().c_str(), group.c_str(), chain.baseLink().c_str(), chain.tipLink().c_str(), count, seed,
              timeout * 1e3);
  std::printf("| solver | success %% | median us | p95 us | mean us | CPU median us | CPU mean us |\n"
              "|---|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& row : rows) {
    if (!row.note.empty()) {
      std::printf("| %s | n/a | | | | | | (%s)\n", row.name.c_str(), row.note.c_str());
      continue;
    }
    std::printf("| %s | %.2f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", row.name.c_str(), row.success_rate,
                row.median_us, row.p95_us, row.mean_us, row.cpu_median_us, row.cpu_mean_us);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string description = sixdof_core::bench::descriptionDir();
  std::string urdf = sixdof_core::bench::defaultUrdf();
  std::string srdf = sixdof_core::bench::defaultSrdf();
  std::string group = "arm", solvers = "analytic,numeric,kdl,kdl_single";
  int count = 10000;
  double timeout = 0.005;
  unsigned long seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) usage("missing value for " + arg);
    const std::string value = argv[++i];
    try {
      parseArgument(arg, value, &urdf, &srdf, &group, &solvers, &count, &timeout, &seed);
    } catch (const std::invalid_argument&) {
      usage("bad value '" + value + "' for " + arg);
    } catch (const std::out_of_range&) {
      usage("value '" + value + "' for " + arg + " is out of range");
    }
  }
  if (count <= 0 || !(timeout > 0.0)) usage("--count and --timeout must be positive");
  try {
    return runBenchmark(urdf, srdf, description, group, solvers, count, timeout, seed);
  } catch (const std::exception& e) {
    std::cerr << "ik_bench: " << e.what() << "\n";
    return 1;
  }
}
