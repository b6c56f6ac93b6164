#include "sixdof_control/control_loop.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "loop_controller.h"

namespace sixdof_control {

using loop::notify;
using loop::pick;
using sixdof_core::GoalState;
using sixdof_core::TrajectoryController;
using sixdof_core::TrajectoryErrorCode;
using sixdof_core::TrajectoryResult;
using sixdof_core::TrajectoryUpdate;

ControlLoop::ControlLoop(ControlLoopConfig config, HardwareInterface& hardware)
    : config_(std::move(config)),
      hardware_(hardware),
      statistics_(config_.rate > 0.0 ? 1.0 / config_.rate : 1.0, std::max<std::size_t>(config_.statistics_window, 1)) {
  const std::size_t n = config_.joints.size();
  if (n == 0) throw std::invalid_argument("ControlLoop: no joints");
  if (config_.limits.size() != n) throw std::invalid_argument("ControlLoop: one joint limit per joint is needed");
  for (std::size_t i = 0; i < n; ++i) {
    if (config_.limits[i].joint != config_.joints[i]) {
      throw std::invalid_argument("ControlLoop: limits[" + std::to_string(i) + "] is joint '" +
                                  config_.limits[i].joint + "', expected '" + config_.joints[i] + "'");
    }
  }
  if (!(config_.rate > 0.0) || !std::isfinite(config_.rate))
    throw std::invalid_argument("ControlLoop: rate must be > 0");
  if (config_.realtime_priority < 0 || config_.realtime_priority > 99) {
    throw std::invalid_argument("ControlLoop: realtime_priority must be 0 (off) or 1..99");
  }
  for (double v : {config_.start_tolerance, config_.read_timeout, config_.velocity_tolerance}) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument("ControlLoop: start_tolerance, read_timeout and velocity_tolerance must be >= 0");
    }
  }
  owner_.assign(n, -1);
  for (sixdof_core::TrajectoryControllerConfig& c : config_.controllers) {
    std::vector<std::size_t> indices;
    c.lower_limits.clear();
    c.upper_limits.clear();
    for (const std::string& joint : c.joints) {
      const auto it = std::find(config_.joints.begin(), config_.joints.end(), joint);
      if (it == config_.joints.end()) {
        throw std::invalid_argument("ControlLoop: joint '" + joint + "' of controller '" + c.name +
                                    "' is not one of the hardware's joints");
      }
      const std::size_t j = static_cast<std::size_t>(it - config_.joints.begin());
      if (owner_[j] >= 0) {
        throw std::invalid_argument("ControlLoop: joint '" + joint + "' belongs to controllers '" +
                                    config_.controllers[static_cast<std::size_t>(owner_[j])].name + "' and '" + c.name +
                                    "'");
      }
      owner_[j] = static_cast<int>(controllers_.size());
      indices.push_back(j);
      const JointLimit& l = config_.limits[j];
      c.lower_limits.push_back(l.has_position_limits ? l.min_position : -std::numeric_limits<double>::infinity());
      c.upper_limits.push_back(l.has_position_limits ? l.max_position : std::numeric_limits<double>::infinity());
    }
    controllers_.push_back(Controller{TrajectoryController(c), indices, nullptr, std::nullopt});
  }
  commander_ = owner_;
  for (sixdof_core::GripperControllerConfig& g : config_.grippers) {
    const auto it = std::find(config_.joints.begin(), config_.joints.end(), g.joint);
    if (it == config_.joints.end()) {
      throw std::invalid_argument("ControlLoop: joint '" + g.joint + "' of gripper '" + g.name +
                                  "' is not one of the hardware's joints");
    }
    if (gripperIndex(g.name) >= 0) throw std::invalid_argument("ControlLoop: two grippers are named '" + g.name + "'");
    const std::size_t j = static_cast<std::size_t>(it - config_.joints.begin());
    const JointLimit& l = config_.limits[j];
    if (!l.has_position_limits) {
      throw std::invalid_argument("ControlLoop: joint '" + g.joint + "' of gripper '" + g.name +
                                  "' needs position limits");
    }
    g.lower = l.min_position;
    g.upper = l.max_position;
    if (commander_[j] == -1) commander_[j] = -2 - static_cast<int>(grippers_.size());
    grippers_.push_back(Gripper{sixdof_core::GripperController(g), j, nullptr, 0.0});
  }
}

ControlLoop::~ControlLoop() { stop(); }

HardwareResult ControlLoop::start(double now) {
  const std::size_t n = config_.joints.size();
  HardwareResult r = hardware_.start();
  std::vector<double> positions(n, 0.0), velocities(n, 0.0);
  if (r.ok()) r = hardware_.read(now, 1.0 / config_.rate, positions, velocities);
  if (!r.ok()) {
    hardware_.stop();
    return r;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  holdAll(positions);
  status_ = LoopStatus{LoopState::kRunning,
                       "",
                       now,
                       positions,
                       hardware_.hasVelocities() ? velocities : std::vector<double>(n, 0.0),
                       positions};
  previous_positions_ = positions;
  hold_ = positions;
  return r;
}

void ControlLoop::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  Notifications done;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state == LoopState::kStopped) return;
    abortAll(GoalState::kAborted, TrajectoryErrorCode::kInvalidGoal, "the control loop stopped", done);
    status_.state = LoopState::kStopped;
  }
  hardware_.stop();
  notify(done);
}

void ControlLoop::spawn() {
  if (running_.exchange(true)) return;
  using Clock = std::chrono::steady_clock;
  origin_ = Clock::now() - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(status().time));
  thread_ = std::thread([this] {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / config_.rate));
    auto next = Clock::now();
    while (running_) {
      next += period;
      std::this_thread::sleep_until(next);
      cycle(std::chrono::duration<double>(Clock::now() - origin_).count());
      // A cycle late by more than a period does not start a burst of catch-up cycles.
      if (Clock::now() > next + period) next = Clock::now();
    }
  });
  if (config_.realtime_priority > 0) {
    sched_param parameters{};
    parameters.sched_priority = config_.realtime_priority;
    const int error = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &parameters);
    if (error != 0) {
      running_ = false;
      thread_.join();
      throw std::runtime_error("ControlLoop: cannot run the loop at SCHED_FIFO priority " +
                               std::to_string(config_.realtime_priority) + ": " + std::strerror(error) +
                               " (needs root, CAP_SYS_NICE or an rtprio limit)");
    }
  }
}

void ControlLoop::cycle(double now) {
  const auto cycle_start = std::chrono::steady_clock::now();
  const std::size_t n = config_.joints.size();
  double period = 1.0 / config_.rate;
  std::size_t clears = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state == LoopState::kStopped) return;
    if (now > status_.time) period = now - status_.time;
    clears = clears_;
  }
  std::vector<double> positions(n, 0.0), velocities(n, 0.0);
  HardwareResult read = hardware_.read(now, period, positions, velocities);
  const double read_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - cycle_start).count();
  if (read.ok() && read_time > config_.read_timeout) {
    std::ostringstream s;
    s << "hardware read took " << read_time << " s, over read_timeout " << config_.read_timeout << " s";
    read = HardwareResult::failure(HardwareStatus::kTimeout, s.str());
  }
  Notifications done;
  std::vector<double> commands;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.time = now;
    // A read begun before a clearFault() that failed: the cleared fault's; this cycle holds, the next read decides.
    const bool stale = !read.ok() && clears != clears_;
    if (stale) {
      status_.commands = hold_;
    } else if (!read.ok()) {
      enterFault(read.message, done);
    } else {
      if (!hardware_.hasVelocities()) {
        for (std::size_t i = 0; i < n; ++i) velocities[i] = (positions[i] - previous_positions_[i]) / period;
      }
      previous_positions_ = positions;
      status_.positions = positions;
      status_.velocities = velocities;
      if (rehold_ && status_.state != LoopState::kFault) {
        holdAll(positions);
        rehold_ = false;
      }
    }
    if (status_.state == LoopState::kFault) {
      status_.commands = hold_;
    } else if (!stale) {
      updateControllers(now, period, done);
      checkLimits(done);
    }
    commands = status_.commands;
  }
  const HardwareResult write = hardware_.write(now, period, commands);
  if (!write.ok()) {
    std::lock_guard<std::mutex> lock(mutex_);
    enterFault(write.message, done);
  }
  const double cycle_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - cycle_start).count();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    statistics_.add(period, cycle_time);
  }
  notify(done);
}

void ControlLoop::updateControllers(double now, double period, Notifications& done) {
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    Controller& c = controllers_[i];
    TrajectoryUpdate u =
        c.controller.update(now, pick(status_.positions, c.joints), pick(status_.velocities, c.joints));
    for (std::size_t k = 0; k < c.joints.size(); ++k) {
      if (commander_[c.joints[k]] == static_cast<int>(i)) status_.commands[c.joints[k]] = u.desired.position[k];
    }
    if (u.finished) endGoal(c, u.state, u.result, done);
    c.last = std::move(u);
  }
  for (std::size_t g = 0; g < grippers_.size(); ++g) {
    Gripper& gripper = grippers_[g];
    if (commander_[gripper.joint] != -2 - static_cast<int>(g)) continue;
    const sixdof_core::GripperUpdate u = gripper.controller.update(now, status_.positions[gripper.joint]);
    const JointLimit& l = config_.limits[gripper.joint];
    const double step =
        l.has_velocity_limits ? l.max_velocity * period : std::abs(u.command_position - gripper.command);
    gripper.command += std::clamp(u.command_position - gripper.command, -step, step);
    status_.commands[gripper.joint] = gripper.command;
    if (u.finished) {
      const std::string message = u.reached_goal                     ? "reached the goal"
                                  : u.state == GoalState::kSucceeded ? "stalled (allow_stalling: counts as success)"
                                                                     : "stalled before reaching the goal";
      endGoal(gripper, u.state, message, done, u.reached_goal, u.stalled);
    }
  }
}

void ControlLoop::checkLimits(Notifications& done) {
  for (std::size_t i = 0; i < controllers_.size(); ++i) {
    Controller& c = controllers_[i];
    if (!c.last) continue;
    for (std::size_t k = 0; k < c.joints.size(); ++k) {
      if (commander_[c.joints[k]] != static_cast<int>(i)) continue;
      const JointLimit& l = config_.limits[c.joints[k]];
      const double q = c.last->desired.position[k];
      const double v = c.last->desired.velocity[k];
      std::ostringstream s;
      if (l.has_position_limits && (q < l.min_position || q > l.max_position)) {
        s << "command " << q << " of joint '" << l.joint << "' is outside its limits [" << l.min_position << ", "
          << l.max_position << "]";
      } else if (l.has_velocity_limits && std::abs(v) > l.max_velocity * (1.0 + config_.velocity_tolerance)) {
        s << "command velocity " << v << " of joint '" << l.joint << "' exceeds its limit " << l.max_velocity
          << " (velocity_tolerance " << config_.velocity_tolerance << ")";
      }
      if (s.str().empty()) continue;
      const std::vector<double> actual = pick(status_.positions, c.joints);
      if (c.controller.active()) {
        endGoal(c, GoalState::kAborted, TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, s.str()), done);
      }
      c.controller.hold(actual);
      for (std::size_t m = 0; m < c.joints.size(); ++m) {
        if (commander_[c.joints[m]] == static_cast<int>(i)) status_.commands[c.joints[m]] = actual[m];
      }
      break;
    }
  }
}

}  // namespace sixdof_control
