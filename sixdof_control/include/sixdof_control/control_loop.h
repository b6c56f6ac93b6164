#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "sixdof_control/controller_host.h"
#include "sixdof_control/hardware_interface.h"
#include "sixdof_control/joint_limits.h"
#include "sixdof_control/period_statistics.h"
#include "sixdof_core/control/gripper_controller.h"
#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_control {

struct ControlLoopConfig {
  std::vector<std::string> joints;  // the hardware's joints, in its order
  std::vector<JointLimit> limits;   // one per joint, in the same order
  // The controllers (controllers.yaml). Each joint belongs to one controller at most; their position limits are
  // taken from `limits` (what the config says there is replaced).
  std::vector<sixdof_core::TrajectoryControllerConfig> controllers;
  // gripper_cmd controllers (controllers.yaml's gripper_cmd blocks), one joint each, which a trajectory controller
  // may command too: the controller whose goal came last commands the joint, the other's goal ends kCanceled. Their
  // position limits are taken from `limits`; a gripper moves its joint's command towards the target at the joint's
  // velocity limit.
  std::vector<sixdof_core::GripperControllerConfig> grippers;
  double rate = 100.0;  // Hz of read -> update -> write
  // A goal whose first point is at time 0 (commanded at once) must start this close to every joint's position
  // (rad or m; MoveIt's allowed_start_tolerance).
  double start_tolerance = 0.01;
  // A read that fails, or takes longer than this (s), is a fault.
  double read_timeout = 0.1;
  // Commands may exceed max_velocity by this fraction: joint_trajectory_controller's splines through the points of
  // a trajectory timed at the limits overshoot them slightly between points.
  double velocity_tolerance = 0.05;
  std::size_t statistics_window = 1000;  // periods the statistics cover
  // 1..99: spawn()'s thread runs SCHED_FIFO at this priority (root or CAP_SYS_NICE), so that other processes'
  // time slices do not delay cycles; 0: normal scheduling.
  int realtime_priority = 0;
};

enum class LoopState {
  kStopped,  // before start() and after stop()
  kRunning,
  kEstop,  // e-stop engaged: holding, goals refused
  kFault,  // a hardware fault: holding where possible, goals refused until clearFault()
};

struct LoopStatus {
  LoopState state = LoopState::kStopped;
  std::string fault;  // the fault's message in kFault
  double time = 0.0;  // of the last cycle, on the loop's clock (s)
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> commands;
};

// ros_control's controller manager loop, without ROS: at a fixed rate it reads the hardware, updates the
// trajectory controllers (sixdof_core's, as the simulator runs them), checks every command against the joint
// limits and writes it. Safety:
// - limits: a goal whose points or segments exceed a joint's position or velocity limit is refused; a command
//   beyond one during execution (spline overshoot past velocity_tolerance) aborts the goal naming the joint, the
//   value and the limit, and the joints hold. Nothing is clamped.
// - faults: a failed or late read, or a failed write, aborts every active goal within that cycle with the plugin's
//   message (naming the joint or device), holds the last positions read (written while the device takes writes)
//   and refuses goals until clearFault().
// - e-stop: setEstop(true) aborts every goal at once and holds; goals are refused until setEstop(false), which
//   holds wherever the joints are then.
// - a goal whose first point is at time 0 and away from the current positions (start_tolerance) is refused.
// Goals and queries are thread-safe; cycle() runs on one thread (spawn()'s, or the caller's in tests).
class ControlLoop {
 public:
  // Throws std::invalid_argument naming the problem: sizes, rate, tolerances, a controller's joint that is not the
  // hardware's or belongs to two controllers, an invalid controller config. The hardware must be init()ed and
  // outlive the loop.
  ControlLoop(ControlLoopConfig config, HardwareInterface& hardware);
  ~ControlLoop();
  ControlLoop(const ControlLoop&) = delete;
  ControlLoop& operator=(const ControlLoop&) = delete;

  // Starts the hardware and reads it once at `now`: every controller holds the positions read.
  HardwareResult start(double now);
  // Ends the thread of spawn() if it runs, aborts active goals, stops the hardware.
  void stop();

  // One cycle at `now` (s on the loop's clock, later than the previous one): read, update, check, write.
  void cycle(double now);
  // Runs cycle() at the rate on a thread of its own (steady clock; the loop's clock then counts from start()'s
  // `now`), until stop(). Throws std::runtime_error naming the reason when realtime_priority cannot be had.
  void spawn();

  // Validates and starts a goal on the controller at the last cycle's time (preempting its active goal, which ends
  // kCanceled). Refused with kInvalidGoal naming why during e-stop or a fault, for an unknown controller, a start
  // away from the current state or beyond a limit; else the controller's own validation.
  sixdof_core::TrajectoryResult setGoal(const std::string& controller, const sixdof_core::TrajectoryGoal& goal,
                                        GoalCallback done);
  // Cancels the controller's active goal (it holds the current positions).
  void cancel(const std::string& controller);
  // The same for a gripper controller: refused with kRefused naming why during e-stop or a fault or for an unknown
  // gripper, else the controller's own validation.
  sixdof_core::GripperResult setGripperGoal(const std::string& gripper, const sixdof_core::GripperGoal& goal,
                                            GripperCallback done);
  void cancelGripper(const std::string& gripper);

  void setEstop(bool engaged);
  // Leaves kFault: the next good read holds wherever the joints are and goals are accepted again.
  void clearFault();

  LoopStatus status() const;
  PeriodSummary statistics() const;
  // The loop's clock now (s): while spawn()'s thread runs, the steady clock counted from start()'s `now`; else the
  // last cycle's time.
  double now() const;
  // Whether the controller commands (some of) its joints now: not when a gripper's goal has taken them.
  bool commands(const std::string& controller) const;
  // The controller's commanded trajectory at `time` (query_state); nullopt for an unknown controller or before
  // start().
  std::optional<sixdof_core::TrajectorySample> sample(const std::string& controller, double time) const;
  // The controller's last update (desired, error; the state topic); nullopt before its first one.
  std::optional<sixdof_core::TrajectoryUpdate> lastUpdate(const std::string& controller) const;

 private:
  struct Controller;
  struct Gripper;
  // Goal callbacks to call once the lock is released.
  using Notifications = std::vector<std::function<void()>>;
  int controllerIndex(const std::string& name) const;
  int gripperIndex(const std::string& name) const;
  std::string refusal() const;
  std::string limitProblem(const sixdof_core::TrajectoryGoal& goal) const;
  // The joint is commanded by trajectory controller `controller` or gripper `gripper` (the other -1) from now on;
  // the goal of the one that commanded it before ends kCanceled.
  void claim(std::size_t joint, int controller, int gripper, const std::string& by, Notifications& done);
  void endGoal(Controller& c, sixdof_core::GoalState state, sixdof_core::TrajectoryResult result, Notifications& done);
  void endGoal(Gripper& g, sixdof_core::GoalState state, const std::string& message, Notifications& done,
               bool reached_goal = false, bool stalled = false);
  void abortAll(sixdof_core::GoalState state, sixdof_core::TrajectoryErrorCode code, const std::string& message,
                Notifications& done);
  void holdAll(const std::vector<double>& positions);
  void enterFault(const std::string& message, Notifications& done);
  void updateControllers(double now, double period, Notifications& done);
  void checkLimits(Notifications& done);
  // Under the lock, runs `stop(entry, done)` on the entry of `entries` (controllers_ or grippers_) named `name` if its
  // goal is active; then notifies what it ended.
  template <class Entry, class Stop>
  void cancelActive(std::vector<Entry>& entries, const std::string& name, Stop stop);

  ControlLoopConfig config_;
  HardwareInterface& hardware_;
  std::vector<Controller> controllers_;
  std::vector<Gripper> grippers_;
  std::vector<int> owner_;  // per joint: its trajectory controller's index, -1 for none
  // Per joint: who commands it now: a trajectory controller's index, or -2 - a gripper's index; -1 for none.
  std::vector<int> commander_;

  mutable std::mutex mutex_;
  LoopStatus status_;
  bool estop_ = false;   // engaged, whatever the state (a fault cleared during an e-stop leaves it kEstop)
  bool rehold_ = false;  // hold wherever the joints are at the next good read (after clearFault, e-stop release)
  // clearFault() calls so far: a read that fails after a clear that came while it was in flight is the cleared
  // fault's (the device was still gone when it began), not a new one.
  std::size_t clears_ = 0;
  std::vector<double> previous_positions_;
  std::vector<double> hold_;  // what a fault writes
  PeriodStatistics statistics_;

  std::atomic<bool> running_{false};
  std::chrono::steady_clock::time_point origin_;  // of the loop's clock while spawned
  std::thread thread_;
};

}  // namespace sixdof_control
