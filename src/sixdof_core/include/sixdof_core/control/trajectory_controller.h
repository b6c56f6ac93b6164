#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sixdof_core/result.h"
#include "sixdof_core/trajectory.h"

namespace sixdof_core {

// Result codes, values as in control_msgs/FollowJointTrajectory.
enum class TrajectoryErrorCode : int {
  kSuccessful = 0,
  kInvalidGoal = -1,
  kInvalidJoints = -2,
  kOldHeaderTimestamp = -3,
  kPathToleranceViolated = -4,
  kGoalToleranceViolated = -5,
};

// message names the offending joint/point/value on failure.
using TrajectoryResult = Result<TrajectoryErrorCode>;

// Per-joint tolerances on |desired - actual|; 0 means "not checked".
struct StateTolerance {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

// A controller's configuration (controllers.yaml: joints + constraints) plus the joints' position limits
// from the URDF. Defaults as in joint_trajectory_controller.
struct TrajectoryControllerConfig {
  std::string name;                      // for messages, e.g. "arm_controller"
  std::vector<std::string> joints;
  std::vector<double> lower_limits;      // per joint; -inf/+inf for unlimited joints
  std::vector<double> upper_limits;
  std::vector<double> path_tolerance;    // constraints/<joint>/trajectory (position), 0 = not checked
  std::vector<double> goal_tolerance;    // constraints/<joint>/goal (position), 0 = not checked
  double goal_time = 0.0;                // constraints/goal_time
  double stopped_velocity_tolerance = 0.01;  // constraints/stopped_velocity_tolerance
};

// A goal's per-joint tolerance (control_msgs/JointTolerance): > 0 overrides the configured value,
// -1 removes the check, 0 keeps the configured value.
struct JointToleranceOverride {
  std::string name;
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

// A FollowJointTrajectory goal without ROS types. Times are seconds on the controller's clock.
struct TrajectoryGoal {
  std::vector<std::string> joint_names;
  std::vector<TrajectoryPoint> points;
  std::vector<JointToleranceOverride> path_tolerance;
  std::vector<JointToleranceOverride> goal_tolerance;
  double goal_time_tolerance = 0.0;  // > 0 overrides goal_time; < 0 sets it to 0
  double start_time = 0.0;           // trajectory header stamp; 0 = when the goal is accepted
};

enum class GoalState { kIdle, kActive, kSucceeded, kAborted, kCanceled };

// What one control step produces.
struct TrajectoryUpdate {
  TrajectorySample desired;  // the command to the joint motors, in config joint order
  TrajectorySample error;    // desired - actual (acceleration error is 0: no measured acceleration)
  GoalState state = GoalState::kIdle;  // of the current/last goal
  bool finished = false;              // the goal ended in this step; result holds why
  TrajectoryResult result;
};

// joint_trajectory_controller semantics, ROS-free:
// - a goal is validated (joints, sizes, times, finite values, position limits, tolerances) and either
//   rejected with kInvalidJoints / kInvalidGoal / kOldHeaderTimestamp or replaces the current one (which
//   the caller reports as preempted). The new trajectory starts from the current desired state when its
//   first point lies in the future.
// - the trajectory is sampled with the joints' position limits as bounds (TrajectorySampler, trajectory.h): between
//   two points within a joint's limits the command stays within them, where a quintic would pass a limit.
// - during execution the path tolerances are checked (kPathToleranceViolated aborts and holds the actual
//   position); after the last point the goal tolerances (positions, velocity with the stopped velocity
//   tolerance) must hold within goal_time, else kGoalToleranceViolated (the final point stays commanded).
// - an empty trajectory stops: it holds the current desired position and succeeds at once.
// - cancel holds the actual position. Without a goal the controller holds its last command.
class TrajectoryController {
 public:
  // Throws std::invalid_argument on an inconsistent config (sizes, duplicates, negative tolerances).
  explicit TrajectoryController(TrajectoryControllerConfig config);

  const TrajectoryControllerConfig& config() const { return config_; }
  const std::vector<std::string>& joints() const { return config_.joints; }

  // Checks a goal without changing anything.
  TrajectoryResult validate(const TrajectoryGoal& goal, double now) const;

  // Validates and, if valid, starts the goal at `now` (replacing an active one).
  TrajectoryResult setGoal(const TrajectoryGoal& goal, double now);

  // Cancels the active goal (if any) and holds the given actual positions.
  void cancel(const std::vector<double>& actual_position);

  // Holds the given positions with no goal (start-up, world reset).
  void hold(const std::vector<double>& position);

  // One control step: samples the trajectory, checks tolerances, finishes the goal when due.
  TrajectoryUpdate update(double now, const std::vector<double>& actual_position,
                          const std::vector<double>& actual_velocity);

  bool active() const { return state_ == GoalState::kActive; }
  GoalState state() const { return state_; }
  // The commanded trajectory (the active goal's, or the hold) sampled at `time`, as the next update() at that
  // time would command it; nullopt before the first hold or goal (joint_trajectory_controller's query_state).
  std::optional<TrajectorySample> sample(double time) const;
  // The time the active trajectory reaches its last point (0 without one).
  double endTime() const { return trajectory_ ? trajectory_->endTime() : 0.0; }

 private:
  TrajectoryResult validateTolerances(const std::vector<JointToleranceOverride>& tolerances,
                                      const char* what) const;
  void holdAt(const std::vector<double>& position);
  std::string jointList() const;

  TrajectoryControllerConfig config_;
  // Knot times are absolute times of the controller's clock. Empty until the first hold/goal.
  std::optional<TrajectorySampler> trajectory_;
  std::vector<StateTolerance> path_tolerance_;   // of the active goal
  std::vector<StateTolerance> goal_tolerance_;
  double goal_time_ = 0.0;
  GoalState state_ = GoalState::kIdle;
  TrajectorySample last_desired_;  // empty before the first update
};

}  // namespace sixdof_core
