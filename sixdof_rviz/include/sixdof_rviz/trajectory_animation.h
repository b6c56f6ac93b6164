#pragma once

#include <optional>
#include <string>
#include <vector>

#include <sixdof_msgs/DisplayTrajectory.h>

#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

// The robot states of a DisplayTrajectory: trajectory_start updated by each point, with time from the start.
struct TrajectoryStates {
  std::vector<JointValues> states;
  std::vector<double> times;  // non-decreasing, seconds since the first state
};

// nullopt with `error` naming the problem for malformed messages (no points, size mismatches, time going back).
// Consecutive trajectories are concatenated in time.
std::optional<TrajectoryStates> toTrajectoryStates(const sixdof_msgs::DisplayTrajectory& msg, std::string* error);

// Which state to show while animating. Realtime follows time_from_start; otherwise every state is shown for
// a fixed time. Without looping the animation ends on the last state.
class TrajectoryAnimation {
 public:
  void start(TrajectoryStates states);
  void clear();
  // Advances by dt seconds. `state_time` nullopt = real time. Returns the index to show (nullopt when empty).
  std::optional<size_t> advance(double dt, bool loop, std::optional<double> state_time);

  bool empty() const { return states_.states.empty(); }
  bool finished() const { return finished_; }
  const TrajectoryStates& states() const { return states_; }

 private:
  TrajectoryStates states_;
  double elapsed_ = 0.0;
  bool finished_ = true;
};

}  // namespace sixdof_rviz
