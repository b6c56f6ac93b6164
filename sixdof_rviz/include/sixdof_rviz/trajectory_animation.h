#pragma once

#include <optional>
#include <string>
#include <vector>

#include <moveit_msgs/DisplayTrajectory.h>

#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

// The robot states of a DisplayTrajectory: trajectory_start updated by each point, with time from the start.
struct TrajectoryStates {
  std::vector<JointValues> states;
  std::vector<double> times;  // non-decreasing, seconds since the first state
};

// nullopt with `error` naming the problem for malformed messages (no points, size mismatches, time going back) and
// for multi-DOF joints (in trajectory_start or a trajectory), which sixdof models do not have.
// Consecutive trajectories are concatenated in time.
std::optional<TrajectoryStates> toTrajectoryStates(const moveit_msgs::DisplayTrajectory& msg, std::string* error);

// Which state to show while animating. Realtime follows time_from_start; otherwise every state is shown for
// a fixed time. Without looping the animation ends on the last state. A trajectory offered while another is
// animating waits until that one ends (or completes a loop) unless it interrupts; only the latest one waits.
class TrajectoryAnimation {
 public:
  // Returns true when the trajectory started at once, false when it waits.
  bool offer(TrajectoryStates states, bool interrupt);
  void start(TrajectoryStates states);
  void clear();
  // Advances by dt seconds. `state_time` nullopt = real time. Returns the index to show (nullopt when empty).
  std::optional<size_t> advance(double dt, bool loop, std::optional<double> state_time);

  bool empty() const { return states_.states.empty(); }
  bool finished() const { return finished_; }
  bool hasPending() const { return pending_.has_value(); }
  const TrajectoryStates& states() const { return states_; }
  // Increases whenever a trajectory starts (to rebuild what depends on the whole trajectory, e.g. a trail).
  unsigned generation() const { return generation_; }

 private:
  TrajectoryStates states_;
  std::optional<TrajectoryStates> pending_;
  unsigned generation_ = 0;
  double elapsed_ = 0.0;
  bool finished_ = true;
};

}  // namespace sixdof_rviz
