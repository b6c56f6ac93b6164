#pragma once

#include <string>

#include "sixdof_core/control/trajectory_controller.h"
#include "sixdof_core/result.h"

namespace sixdof_core {

// controllers.yaml gripper_controller/gripper_cmd parameters plus the finger joint's URDF limits.
// Defaults as in ros_controllers' gripper_action_controller, except allow_stalling (see below).
struct GripperControllerConfig {
  std::string name;    // for messages, e.g. "gripper_controller"
  std::string joint;   // the commanded finger joint (the other finger mimics it)
  double lower = 0.0;  // URDF position limits (finger opening, m)
  double upper = 0.0;
  double effort_limit = 0.0;             // URDF effort limit (N); max_effort 0 means this
  double goal_tolerance = 0.01;          // |target - position| below which the goal is reached
  // The finger's progress towards the target, averaged over stall_timeout, below which it counts as stalled.
  // gripper_action_controller compares the instantaneous velocity, which a finger pressed on an object in physics
  // never settles below: it jitters (a prismatic finger by +-0.01 m/s within 20 um) or rocks back and forth (a
  // revolute linkage's master between 0.249 and 0.270 rad on a sphere at rest). Only movement towards the target
  // counts: going back and forth makes no progress.
  double stall_velocity_threshold = 0.001;
  double stall_timeout = 1.0;               // s without progress until "stalled"
  // Whether a stall ends the goal as succeeded (a grasp: the fingers closed on an object) rather than
  // aborted. gripper_action_controller aborts on stall (newer versions: allow_stalling, default false).
  bool allow_stalling = false;
};

struct GripperGoal {
  double position = 0.0;    // target finger opening (m)
  double max_effort = 0.0;  // N; 0 = the URDF effort limit
};

// Why a goal was rejected.
enum class GripperStatus {
  kOk = 0,
  kInvalidArgument,  // not finite, negative effort
  kOutOfLimits,      // position outside the joint limits, effort above the effort limit
  kRefused,          // whoever hosts the controller takes no goals now (sixdof_control: e-stop, fault, stopped)
};

using GripperResult = Result<GripperStatus>;

// One control step's command and the goal's status.
struct GripperUpdate {
  double command_position = 0.0;
  double command_max_effort = 0.0;  // always > 0 (0 is resolved to the effort limit)
  GoalState state = GoalState::kIdle;
  bool finished = false;  // the goal ended in this step
  bool reached_goal = false;
  bool stalled = false;
  double position = 0.0;  // actual position at this step
};

// GripperCommand semantics (gripper_action_controller): the finger servos to the target with bounded
// force. The goal succeeds as soon as |target - position| < goal_tolerance (reached_goal). Otherwise it ends
// stalled once the finger has not come closer to the target by more than stall_velocity_threshold x stall_timeout
// for longer than stall_timeout (its progress averaged below the threshold speed): succeeded when allow_stalling
// (closing on an object is a grasp), aborted otherwise. The command stays in force after either, so a stalled grip
// keeps squeezing with max_effort. Cancel holds the actual position with the default effort.
class GripperController {
 public:
  // Throws std::invalid_argument on a bad config (limits, non-positive effort limit, negative values).
  explicit GripperController(GripperControllerConfig config);

  const GripperControllerConfig& config() const { return config_; }

  // Rejects NaN/inf, positions outside [lower, upper], max_effort < 0 or > effort_limit.
  GripperResult validate(const GripperGoal& goal) const;
  // Validates and starts the goal at `now` (replacing an active one).
  GripperResult setGoal(const GripperGoal& goal, double now);
  void cancel(double actual_position);
  // Holds a position with the default effort, no goal (start-up, world reset, another controller took over).
  void hold(double position);

  GripperUpdate update(double now, double position);

  bool active() const { return state_ == GoalState::kActive; }
  GoalState state() const { return state_; }

 private:
  GripperControllerConfig config_;
  bool has_command_ = false;
  double command_position_ = 0.0;
  double command_effort_ = 0.0;
  // The finger's distance to the target (|target - position|) when it last came closer by more than
  // stall_velocity_threshold x stall_timeout (or the goal started), and when that was.
  bool progress_anchored_ = false;
  double progress_distance_ = 0.0;
  double progress_time_ = 0.0;
  GoalState state_ = GoalState::kIdle;
};

}  // namespace sixdof_core
