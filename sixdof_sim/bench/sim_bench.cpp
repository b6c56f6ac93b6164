// sim_bench: real-time factor of the free-running World at its 1 kHz step with the arm following a
// sinusoidal joint trajectory, the gripper opening and closing, the default world's objects plus
// extra ones up to --objects dynamic objects, and the process's peak memory.
//
//   sim_bench [--urdf FILE] [--world FILE] [--package-root DIR] [--seconds SIM_SECONDS] [--objects N]
//             [--no-grasp-fix]
//
// Defaults: the installed sixdof_description URDF and sixdof_sim's worlds/table_top.yaml, package://
// URIs resolved in the install space's share directory, 20 s of simulated time, 5 dynamic objects.

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <sixdof_core/robot_model.h>

#include "bench_util.h"
#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/world.h"
#include "sixdof_sim/world_file.h"

namespace {

using sixdof_sim::bench::shareDir;
using sixdof_sim::GraspFixConfig;
using sixdof_sim::ObjectSpec;
using sixdof_sim::World;
using sixdof_sim::WorldOptions;
using sixdof_sim::WorldSpec;

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
  sixdof_sim::bench::CommandLine cli;
  cli.number("--seconds", "SIM_SECONDS", &seconds);
  cli.number("--objects", "N", &dynamic_objects);
  cli.flag("--no-grasp-fix", &no_grasp_fix);
  if (!cli.parse(argc, argv) || !(seconds > 0.0) || dynamic_objects < 0) return cli.usage(argv[0]);
  const bool grasp_fix = !no_grasp_fix;

  const std::string urdf = sixdof_core::readTextFile(cli.urdf_path);
  WorldSpec spec = sixdof_sim::loadWorldFile(cli.world_path);
  int dynamic = 0;
  for (const ObjectSpec& o : spec.objects) dynamic += o.is_static ? 0 : 1;
  // Extra dynamic boxes in a row at the back of the table until the requested count is reached.
  for (int k = 0; dynamic < dynamic_objects; ++k, ++dynamic) {
    ObjectSpec box;
    box.name = "bench_box_" + std::to_string(k);
    box.shape.box_size = Eigen::Vector3d(0.03, 0.03, 0.05);
    box.mass = 0.08;
    box.pose.translation() = Eigen::Vector3d(0.65, -0.4 + 0.08 * k, 0.025);
    spec.objects.push_back(box);
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

  // Sinusoidal arm trajectory about a mid pose, position + velocity feed-forward every step.
  const std::vector<std::string> arm = {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"};
  const std::vector<double> centre = {0.0, 0.3, 0.4, 0.0, 0.6, 0.0};
  const double amplitude = 0.4;
  const double omega = 2.0 * M_PI * 0.25;
  auto check = [](const sixdof_sim::Result& r) {
    if (!r.ok()) {
      std::cerr << "sim_bench: command rejected: " << r.message << "\n";
      std::exit(1);
    }
  };
  world.setPreStepCallback([&](double t) {
    for (size_t j = 0; j < arm.size(); ++j) {
      const double phase = omega * t + 0.7 * static_cast<double>(j);
      check(world.setPositionTarget(arm[j], centre[j] + amplitude * std::sin(phase),
                                    amplitude * omega * std::cos(phase)));
    }
    check(world.setPositionTarget("finger1_joint", 0.02 + 0.015 * std::sin(2.0 * omega * t)));
  });

  const auto steps = static_cast<std::uint64_t>(std::llround(seconds / world.timeStep()));
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpuSeconds();
  world.step(steps);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = cpuSeconds() - cpu_start;

  std::printf("sim_bench: %d dynamic objects (%zu objects in all), grasp fix %s\n", dynamic, spec.objects.size(),
              grasp_note.c_str());
  std::printf("  steps %llu of %.1f ms, simulated %.2f s, wall %.3f s\n", static_cast<unsigned long long>(steps),
              world.timeStep() * 1e3, world.simTime(), wall);
  std::printf("  real-time factor %.1fx wall clock (%.1f us per step)\n", world.simTime() / wall, wall / steps * 1e6);
  // On a shared machine the wall clock includes time other processes held the CPU.
  std::printf("  real-time factor %.1fx CPU time (%.1f us per step)\n", world.simTime() / cpu, cpu / steps * 1e6);
  std::printf("  peak RSS %.1f MB\n", peakRssMb());
  return 0;
}
