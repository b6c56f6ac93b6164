// control_loop_bench: the period jitter of the control loop on its own thread with the mock plugin, against a bare
// sleep_until loop at the same rate in the same run (the timer jitter the machine gives any loop).
//
//   control_loop_bench [--urdf FILE] [--joint-limits FILE] [--rate HZ] [--seconds S] [--time-constant S]
//                      [--realtime-priority N]
//
// Defaults: the installed sixdof_description's URDF and joint_limits.yaml, every moving joint of the URDF in one
// trajectory controller, 100 Hz, 20 s each, mock time constant 0.05 s. The joints follow a slow back-and-forth
// trajectory the whole time. With --realtime-priority both loops run SCHED_FIFO at that priority.

#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "sixdof_control/control_loop.h"
#include "sixdof_control/hardware_loader.h"
#include "sixdof_core/robot_model.h"

namespace {

using sixdof_control::PeriodStatistics;
using sixdof_control::PeriodSummary;

std::filesystem::path shareDir() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().parent_path().parent_path() / "share";
}

// Periods of a loop that only sleeps until its next period, like the control loop's thread.
PeriodSummary timerLoop(double rate, double seconds) {
  using Clock = std::chrono::steady_clock;
  const std::size_t count = static_cast<std::size_t>(rate * seconds);
  PeriodStatistics statistics(1.0 / rate, count);
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  auto next = Clock::now();
  auto last = next;
  for (std::size_t i = 0; i < count; ++i) {
    next += period;
    std::this_thread::sleep_until(next);
    const auto now = Clock::now();
    statistics.add(std::chrono::duration<double>(now - last).count(), 0.0);
    last = now;
  }
  return statistics.summary();
}

// timerLoop on a thread of its own at the control loop's priority.
PeriodSummary bareLoop(double rate, double seconds, int priority) {
  PeriodSummary summary;
  std::thread thread([&] {
    if (priority > 0) {
      sched_param parameters{};
      parameters.sched_priority = priority;
      if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &parameters) != 0) return;
    }
    summary = timerLoop(rate, seconds);
  });
  thread.join();
  return summary;
}

void print(const char* what, const PeriodSummary& s, bool cycle) {
  std::printf(
      "  %-26s period p50 %.3f ms, p99 %.3f ms; period error p50 %.3f ms, p99 %.3f ms, max %.3f ms; "
      "%zu of %zu periods over twice the nominal\n",
      what, s.period_p50 * 1e3, s.period_p99 * 1e3, s.error_p50 * 1e3, s.error_p99 * 1e3, s.error_max * 1e3, s.overruns,
      s.count);
  if (cycle)
    std::printf("  %-26s cycle (read, update, write) p50 %.3f ms, p99 %.3f ms\n", "", s.cycle_p50 * 1e3,
                s.cycle_p99 * 1e3);
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s [--urdf FILE] [--joint-limits FILE] [--rate HZ] [--seconds S] [--time-constant S] "
               "[--realtime-priority N]\n",
               argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string urdf = (shareDir() / "sixdof_description" / "urdf" / "sixdof.urdf").string();
  std::string joint_limits = (shareDir() / "sixdof_description" / "config" / "joint_limits.yaml").string();
  double rate = 100.0, seconds = 20.0, time_constant = 0.05;
  int priority = 0;
  for (int i = 1; i < argc; i += 2) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage(argv[0]);
    try {
      if (arg == "--urdf")
        urdf = argv[i + 1];
      else if (arg == "--joint-limits")
        joint_limits = argv[i + 1];
      else if (arg == "--rate")
        rate = std::stod(argv[i + 1]);
      else if (arg == "--seconds")
        seconds = std::stod(argv[i + 1]);
      else if (arg == "--time-constant")
        time_constant = std::stod(argv[i + 1]);
      else if (arg == "--realtime-priority")
        priority = std::stoi(argv[i + 1]);
      else
        return usage(argv[0]);
    } catch (const std::exception&) {
      return usage(argv[0]);
    }
  }
  if (!(rate > 0.0) || !(seconds > 0.0) || !(time_constant >= 0.0) || priority < 0 || priority > 99) {
    return usage(argv[0]);
  }

  const sixdof_core::RobotModel model(sixdof_core::readTextFile(urdf), "",
                                      sixdof_core::PackageResolver::fromSearchRoots({shareDir().string()}));
  sixdof_control::ControlLoopConfig config;
  config.joints = model.variableNames();
  config.limits = sixdof_control::loadJointLimits(model, YAML::LoadFile(joint_limits), config.joints);
  config.rate = rate;
  config.realtime_priority = priority;
  config.statistics_window = static_cast<std::size_t>(rate * seconds) + 10;
  sixdof_core::TrajectoryControllerConfig controller;
  controller.name = "bench_controller";
  controller.joints = config.joints;
  controller.path_tolerance.assign(config.joints.size(), 0.0);
  controller.goal_tolerance.assign(config.joints.size(), 0.0);
  config.controllers = {controller};

  sixdof_control::HardwareLoader loader;
  auto hardware = loader.load("mock");
  const auto init = hardware->init(config.joints, YAML::Load("{time_constant: " + std::to_string(time_constant) + "}"));
  if (!init.ok()) {
    std::fprintf(stderr, "control_loop_bench: %s\n", init.message.c_str());
    return 1;
  }
  sixdof_control::ControlLoop loop(config, *hardware);
  if (!loop.start(0.0).ok()) return 1;
  // Back and forth between the middle of each joint's range and a tenth of its range away, 2 s per leg.
  sixdof_core::TrajectoryGoal goal;
  goal.joint_names = config.joints;
  for (int leg = 1; leg <= static_cast<int>(seconds / 2.0) + 1; ++leg) {
    sixdof_core::TrajectoryPoint point;
    for (const sixdof_control::JointLimit& l : config.limits) {
      const double middle = l.has_position_limits ? 0.5 * (l.min_position + l.max_position) : 0.0;
      const double span = l.has_position_limits ? 0.1 * (l.max_position - l.min_position) : 0.5;
      point.positions.push_back(middle + (leg % 2 ? span : 0.0));
      point.velocities.push_back(0.0);
    }
    point.time_from_start = 2.0 * leg;
    goal.points.push_back(point);
  }
  const auto accepted = loop.setGoal("bench_controller", goal, nullptr);
  if (!accepted.ok()) {
    std::fprintf(stderr, "control_loop_bench: goal refused: %s\n", accepted.message.c_str());
    return 1;
  }
  try {
    loop.spawn();
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "control_loop_bench: %s\n", e.what());
    return 1;
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const PeriodSummary control = loop.statistics();
  loop.stop();
  const PeriodSummary bare = bareLoop(rate, seconds, priority);

  std::printf(
      "control_loop_bench: mock plugin (time constant %.3f s), %zu joints in one trajectory controller, "
      "%.0f Hz, %.1f s each, %s\n",
      time_constant, config.joints.size(), rate, seconds,
      priority > 0 ? ("SCHED_FIFO priority " + std::to_string(priority)).c_str() : "normal scheduling");
  print("control loop:", control, true);
  print("bare sleep_until loop:", bare, false);
  std::printf("  p99 period error, control loop / bare loop: %.2fx\n",
              bare.error_p99 > 0.0 ? control.error_p99 / bare.error_p99 : 0.0);
  return 0;
}
