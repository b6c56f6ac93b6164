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
//
// With position bounds (a controller's joint limits), a joint's sample between two points that both lie within its
// bounds lies within them too. A quintic (or cubic) through such points can pass a bound between them where the
// motion the points were sampled from changes its acceleration abruptly: a time-optimal profile switching from
// accelerating to braking, a blend arc meeting a straight segment along a joint's limit (there, at 0.1 s between
// points, by up to ~2e-4 rad); and a polynomial ending on a bound can round past it by an ulp. Such a sample is
// the bound, at rest (zero velocity and acceleration), as joint_limits_interface's position saturation would make
// it on ros_control hardware. Points are never moved: a point outside its bounds is sampled as given, and so are
// the segments next to it (whoever accepts points checks them against the limits).
class TrajectorySampler {
 public:
  // Throws std::invalid_argument naming the problem unless: at least one point; positions sized like joint_names;
  // velocities and accelerations empty or sized like joint_names on each point (points may differ); finite values
  // and times; strictly increasing times.
  explicit TrajectorySampler(Trajectory trajectory);
  // Bounded positions (see above): lower and upper per joint (-inf/+inf: unbounded). Throws std::invalid_argument
  // as above, and unless both are sized like joint_names with lower <= upper (no NaN).
  TrajectorySampler(Trajectory trajectory, std::vector<double> lower, std::vector<double> upper);

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
  std::vector<double> lower_;                      // [joint]; empty: unbounded
  std::vector<double> upper_;
};

}  // namespace sixdof_core
