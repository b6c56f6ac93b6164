#pragma once

#include <cstddef>
#include <vector>

#include <sixdof_core/spline.h>

namespace sixdof_sim {

// One waypoint (positions, optional velocities and accelerations, time) and the spline segments are the core's.
using sixdof_core::InterpolationType;
using sixdof_core::interpolationType;
using sixdof_core::JointSpline;
using sixdof_core::TrajectoryPoint;

// Desired state of all joints at one instant.
struct TrajectorySample {
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> acceleration;
};

// A piecewise-polynomial trajectory over absolute times. Knot i is reached at times[i]; segment i joins
// knot i and i+1. Before the first knot it holds the first knot's positions, after the last knot the last
// knot's positions, both at rest (zero velocity and acceleration): the robot is meant to stop there.
class JointTrajectory {
 public:
  // Throws std::invalid_argument on inconsistent input (no knots, sizes, non-increasing times); callers
  // validate user input beforehand and report it as a result code.
  JointTrajectory(std::vector<double> times, std::vector<TrajectoryPoint> knots);

  TrajectorySample sample(double time) const;

  double startTime() const { return times_.front(); }
  double endTime() const { return times_.back(); }
  std::size_t dof() const { return dof_; }
  std::size_t segmentCount() const { return splines_.size(); }
  InterpolationType segmentType(std::size_t segment) const { return types_.at(segment); }
  const TrajectoryPoint& lastKnot() const { return knots_.back(); }

 private:
  std::size_t dof_;
  std::vector<double> times_;
  std::vector<TrajectoryPoint> knots_;
  std::vector<InterpolationType> types_;
  std::vector<std::vector<JointSpline>> splines_;  // [segment][joint]
};

}  // namespace sixdof_sim
