#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace sixdof_sim {

// One waypoint of a joint trajectory (trajectory_msgs/JointTrajectoryPoint without ROS). velocities and
// accelerations are either empty or have one value per joint.
struct TrajectoryPoint {
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> accelerations;
  double time_from_start = 0.0;
};

// Desired state of all joints at one instant.
struct TrajectorySample {
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> acceleration;
};

// How a segment is interpolated; chosen from the derivatives both of its end points carry
// (joint_trajectory_controller's spline rules).
enum class InterpolationType { LINEAR, CUBIC, QUINTIC };

// Polynomial p(t) = sum c[k] t^k, t in [0, duration], for one joint over one segment.
class JointSpline {
 public:
  // Linear: positions only. Cubic: positions and velocities. Quintic: positions, velocities, accelerations.
  JointSpline(InterpolationType type, double duration, double p0, double v0, double a0, double p1, double v1,
              double a1);

  // t is clamped to [0, duration]: the segment holds its end points outside its time span.
  void sample(double t, double& position, double& velocity, double& acceleration) const;

 private:
  std::array<double, 6> c_{};
  double duration_;
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

// The interpolation the two points allow together: the highest derivative order both carry.
InterpolationType interpolationType(const TrajectoryPoint& from, const TrajectoryPoint& to);

}  // namespace sixdof_sim
