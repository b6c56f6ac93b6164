// camera_bench: frame time of a simulated RGB-D camera (colour + depth) and the World's real-time factor
// headless with that camera rendering at its rate in simulated time, against the same run without it.
// The arm's joints follow sinusoids (every actuated joint, whatever the URDF) so the links move between
// frames, and the default world's objects are on the table.
//
//   camera_bench [--urdf FILE] [--world FILE] [--package-root DIR] [--seconds SIM_SECONDS] [--frames N]
//                [--width W] [--height H] [--rate HZ] [--threads N]
//
// The camera is the world file's first one; without one, a 60 deg camera at (1.1, 0, 0.6) looking back
// down at the table. Defaults: the installed URDF and table_top.yaml, 640 x 480, 15 Hz, 10 s, 200 frames.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <sixdof_core/robot_model.h>

#include "bench_util.h"
#include "sixdof_sim/camera.h"
#include "sixdof_sim/world.h"
#include "sixdof_sim/world_file.h"

namespace {

using sixdof_sim::bench::shareDir;
using sixdof_sim::CameraFrame;
using sixdof_sim::CameraRenderer;
using sixdof_sim::CameraSpec;
using sixdof_sim::World;
using sixdof_sim::WorldSpec;

double percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const size_t i = std::min(values.size() - 1, static_cast<size_t>(std::ceil(q * values.size())) - 1);
  return values[i];
}

// Every non-mimic joint swings about the middle of its range.
void moveJoints(World& world) {
  world.setPreStepCallback([&world](double t) {
    const auto& joints = world.joints();
    for (size_t j = 0; j < joints.size(); ++j) {
      if (!joints[j].mimic_of.empty()) continue;
      const double mid = 0.5 * (joints[j].lower + joints[j].upper);
      const double amplitude = 0.25 * (joints[j].upper - joints[j].lower);
      world.setPositionTarget(joints[j].name, mid + amplitude * std::sin(2.0 * M_PI * 0.25 * t + 0.7 * j));
    }
  });
}

// Simulated seconds per wall-clock second over `seconds`, rendering camera 0 at its rate when given one.
double realTimeFactor(World& world, CameraRenderer* renderer, double seconds, double rate, int* frames) {
  CameraFrame frame;
  const auto steps = static_cast<std::uint64_t>(std::llround(seconds / world.timeStep()));
  const double start_sim = world.simTime();
  double next_frame = start_sim;
  *frames = 0;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t s = 0; s < steps; ++s) {
    if (renderer != nullptr && world.simTime() + 1e-9 >= next_frame) {
      renderer->render(0, &frame);
      ++*frames;
      next_frame = (std::floor(world.simTime() * rate + 1e-6) + 1.0) / rate;
    }
    world.step(1);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return (world.simTime() - start_sim) / wall;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0, rate = 15.0;
  int frames = 200, width = 640, height = 480, threads = 0;
  sixdof_sim::bench::CommandLine cli;
  cli.number("--seconds", "SIM_SECONDS", &seconds);
  cli.number("--frames", "N", &frames);
  cli.number("--width", "W", &width);
  cli.number("--height", "H", &height);
  cli.number("--rate", "HZ", &rate);
  cli.number("--threads", "N", &threads);
  if (!cli.parse(argc, argv) || !(seconds > 0.0) || frames < 1 || threads < 0) return cli.usage(argv[0]);

  const std::string urdf = sixdof_core::readTextFile(cli.urdf_path);
  WorldSpec spec = sixdof_sim::loadWorldFile(cli.world_path);
  if (spec.cameras.empty()) {
    CameraSpec camera;
    camera.name = "bench";
    camera.pose.translation() = Eigen::Vector3d(1.1, 0.0, 0.6);
    // Yaw pi (facing the robot), then pitched 35 deg down.
    camera.pose.linear() = (Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(35.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()))
                               .toRotationMatrix();
    spec.cameras.push_back(camera);
  }
  spec.cameras.resize(1);
  spec.cameras[0].width = width;
  spec.cameras[0].height = height;
  spec.cameras[0].rate = rate;
  const sixdof_sim::Result valid = sixdof_sim::validateCameraSpec(spec.cameras[0]);
  if (!valid.ok()) {
    std::cerr << "camera_bench: " << valid.message << "\n";
    return 2;
  }

  sixdof_sim::WorldOptions options;
  options.package_search_roots = {cli.package_root.empty() ? shareDir().string() : cli.package_root};
  options.grasp_fix_enabled = false;
  try {
    World world(urdf, spec, options);
    moveJoints(world);
    const auto build_start = std::chrono::steady_clock::now();
    CameraRenderer renderer(world, spec, sixdof_sim::CameraRendererOptions{threads});
    const double build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - build_start).count();

    // Frame times, the arm moving 1 / rate of simulated time between frames.
    CameraFrame frame;
    std::vector<double> ms;
    const auto steps_per_frame = static_cast<std::uint64_t>(std::llround(1.0 / rate / world.timeStep()));
    for (int f = 0; f < frames; ++f) {
      world.step(steps_per_frame);
      const auto start = std::chrono::steady_clock::now();
      renderer.render(0, &frame);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    size_t hits = 0;
    for (float d : frame.depth) hits += std::isnan(d) ? 0 : 1;

    int rendered = 0;
    const double rtf_without = realTimeFactor(world, nullptr, seconds, rate, &rendered);
    const double rtf_with = realTimeFactor(world, &renderer, seconds, rate, &rendered);

    std::printf("camera_bench: %dx%d, %.0f deg horizontal fov, %s render thread(s), scene built in %.1f ms\n", width,
                height, spec.cameras[0].horizontal_fov * 180.0 / M_PI,
                threads > 0 ? std::to_string(threads).c_str() : "one per hardware", build_ms);
    std::printf("  frame time over %d frames: median %.2f ms, p95 %.2f ms, max %.2f ms (%.0f%% of pixels hit)\n",
                frames, percentile(ms, 0.5), percentile(ms, 0.95), percentile(ms, 1.0),
                100.0 * static_cast<double>(hits) / static_cast<double>(frame.depth.size()));
    std::printf("  real-time factor over %.1f s simulated: %.1fx without camera, %.1fx with the camera at %.0f Hz"
                " (%d frames)\n",
                seconds, rtf_without, rtf_with, rate, rendered);
  } catch (const std::exception& e) {
    std::cerr << "camera_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
