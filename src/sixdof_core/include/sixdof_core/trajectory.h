#pragma once

#include <string>
#include <vector>

namespace sixdof_core {

// One waypoint of a joint trajectory (trajectory_msgs/JointTrajectoryPoint without effort).
struct TrajectoryPoint {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> accelerations;
  double time_from_start = 0.0;  // s
};

struct Trajectory {
  std::vector<std::string> joint_names;
  std::vector<TrajectoryPoint> points;

  double duration() const { return points.empty() ? 0.0 : points.back().time_from_start; }
};

// Empty if the trajectory is well formed: at least one point, positions sized like joint_names,
// velocities/accelerations either empty or sized like joint_names (the same on every point),
// finite values, times starting at >= 0 and strictly increasing. Otherwise a message naming the problem.
std::string validateTrajectory(const Trajectory& trajectory);

struct TrajectorySample {
  bool ok = false;
  std::string message;
  TrajectoryPoint point;
};

// The state at time t (0 <= t <= duration) interpolated like ros_control's joint_trajectory_controller:
// quintic between points that carry positions, velocities and accelerations, cubic with velocities
// only, linear with positions only. Before the first point's time the first point holds.
TrajectorySample sampleTrajectory(const Trajectory& trajectory, double time);

}  // namespace sixdof_core
