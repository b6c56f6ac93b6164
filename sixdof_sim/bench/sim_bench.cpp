// sim_bench: real-time factor of the free-running World at its 1 kHz step with the arm following a
// sinusoidal joint trajectory (every actuated joint, whatever the URDF), the gripper opening and closing, the
// world's objects plus extra boxes on its table up to --objects dynamic objects, and the process's peak memory.
//
//   sim_bench [--urdf FILE] [--world FILE] [--package-root DIR] [--seconds SIM_SECONDS] [--objects N]
//             [--no-grasp-fix] [--scenario FILE]
//
// Defaults: the installed sixdof_description URDF and sixdof_sim's worlds/table_top.yaml, package://
// URIs resolved in the install space's share directory, 20 s of simulated time, 5 dynamic objects.
// --scenario FILE writes the run as JSON (bench_scenario.h): what another simulator needs to repeat the same
// work (bench/pybullet_world.py), and this run's timings.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <sixdof_core/robot_model.h>

#include "bench_scenario.h"
#include "bench_util.h"
#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/world.h"
#include "sixdof_sim/world_file.h"

namespace {

using sixdof_sim::bench::shareDir;
using sixdof_sim::GraspFixConfig;
using sixdof_sim::World;
using sixdof_sim::WorldOptions;
using sixdof_sim::WorldSpec;
namespace bench = sixdof_sim::bench;

double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 20.0;
  int dynamic_objects = 5;
  bool no_grasp_fix = false;
  std::string scenario_path;
  bench::CommandLine cli;
  cli.number("--seconds", "SIM_SECONDS", &seconds);
  cli.number("--objects", "N", &dynamic_objects);
  cli.flag("--no-grasp-fix", &no_grasp_fix);
  cli.text("--scenario", "FILE", &scenario_path);
  if (!cli.parse(argc, argv) || !(seconds > 0.0) || dynamic_objects < 0) return cli.usage(argv[0]);
  const bool grasp_fix = !no_grasp_fix;

  const std::string urdf = sixdof_core::readTextFile(cli.urdf_path);
  WorldSpec spec = sixdof_sim::loadWorldFile(cli.world_path);
  std::string error;
  const int dynamic = bench::addTableBoxes(&spec, dynamic_objects, &error);
  if (dynamic < 0) {
    std::cerr << "sim_bench: " << error << "\n";
    return 2;
  }

  WorldOptions options;
  options.package_search_roots = {cli.package_root.empty() ? shareDir().string() : cli.package_root};
  options.grasp_fix_enabled = grasp_fix;
  std::string grasp_note = grasp_fix ? "on (URDF block)" : "off";
  if (grasp_fix && !sixdof_sim::parseGraspFixConfig(urdf)) {
    // The provisional URDF has no gazebo_grasp_fix block: bench with the paper's values.
    GraspFixConfig paper;
    paper.arm_name = "arm";
    paper.palm_link = "link6";
    paper.gripper_links = {"finger1", "finger2"};
    options.grasp_fix_config = paper;
    grasp_note = "on (paper's values; the URDF has no block)";
  }
  World world(urdf, spec, options);

  const std::vector<bench::JointSwing> swings = bench::jointSwings(world.joints());
  world.setPreStepCallback([&](double t) {
    for (const bench::JointSwing& s : swings) {
      const sixdof_sim::Result r = world.setPositionTarget(s.joint, s.position(t), s.velocity(t));
      if (!r.ok()) {
        std::cerr << "sim_bench: command rejected: " << r.message << "\n";
        std::exit(1);
      }
    }
  });

  // The first 5 s are timed apart too: objects starting on the table settle and fall asleep in about 2.5 s.
  const auto steps = static_cast<std::uint64_t>(std::llround(seconds / world.timeStep()));
  const std::uint64_t settle = std::min<std::uint64_t>(steps, std::llround(5.0 / world.timeStep()));
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpuSeconds();
  world.step(settle);
  const auto settled = std::chrono::steady_clock::now();
  world.step(steps - settle);
  const auto end = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(end - start).count();
  const double cpu = cpuSeconds() - cpu_start;
  const double wall_settled = std::chrono::duration<double>(end - settled).count();

  std::printf("sim_bench: %d dynamic objects (%zu objects in all), grasp fix %s\n", dynamic, spec.objects.size(),
              grasp_note.c_str());
  std::printf("  steps %llu of %.1f ms, simulated %.2f s, wall %.3f s\n", static_cast<unsigned long long>(steps),
              world.timeStep() * 1e3, world.simTime(), wall);
  std::printf("  real-time factor %.1fx wall clock (%.1f us per step)\n", world.simTime() / wall, wall / steps * 1e6);
  // On a shared machine the wall clock includes time other processes held the CPU.
  std::printf("  real-time factor %.1fx CPU time (%.1f us per step)\n", world.simTime() / cpu, cpu / steps * 1e6);
  if (steps > settle) {
    std::printf("  after the first %.0f s: %.1f us per step\n", settle * world.timeStep(),
                wall_settled / static_cast<double>(steps - settle) * 1e6);
  }
  std::printf("  peak RSS %.1f MB\n", peakRssMb());

  if (!scenario_path.empty()) {
    std::ofstream out(scenario_path);
    bench::Timing timing{steps, wall, cpu, steps - settle, wall_settled};
    bench::writeScenario(out, cli.urdf_path, options, spec, world, swings, timing);
    if (!out) {
      std::cerr << "sim_bench: cannot write " << scenario_path << "\n";
      return 1;
    }
  }
  return 0;
}
