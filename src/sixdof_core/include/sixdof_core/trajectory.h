#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sixdof_core/spline.h"

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

// The interpolation two points allow together: the highest derivative order both carry.
InterpolationType interpolationType(const TrajectoryPoint& from, const TrajectoryPoint& to);

// The state of all joints at one instant, in the trajectory's joint order.
struct TrajectorySample {
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> acceleration;
};

// A trajectory ready to be sampled, interpolated like ros_control's joint_trajectory_controller: each segment
// quintic when both of its points carry velocities and accelerations, cubic with velocities, linear with
// positions only (a point's missing derivatives count as zero at the point). Outside the points' times it holds
// at rest (zero velocity and acceleration): before the first point's time the first point's positions, after the
// last point's time the last point's positions, where the robot is meant to stop. At a point's time the sample is
// the point (its velocities and accelerations as given).
//
// Times are the points' time_from_start on whatever clock the caller samples with (a controller gives absolute
// times of its clock), so they may be negative. Validated once, the segments computed once: sampling is cheap.
class TrajectorySampler {
 public:
  // Throws std::invalid_argument naming the problem unless: at least one point; positions sized like joint_names;
  // velocities and accelerations empty or sized like joint_names on each point (points may differ); finite values
  // and times; strictly increasing times.
  explicit TrajectorySampler(Trajectory trajectory);

  // Throws std::invalid_argument for a non-finite time.
  TrajectorySample sample(double time) const;

  const Trajectory& trajectory() const { return trajectory_; }
  double startTime() const { return trajectory_.points.front().time_from_start; }
  double endTime() const { return trajectory_.points.back().time_from_start; }
  std::size_t segmentCount() const { return types_.size(); }
  InterpolationType segmentType(std::size_t segment) const { return types_.at(segment); }

 private:
  Trajectory trajectory_;
  std::size_t dof_ = 0;
  std::vector<InterpolationType> types_;           // [segment]
  std::vector<std::vector<JointSpline>> splines_;  // [segment][joint]
};

}  // namespace sixdof_core
