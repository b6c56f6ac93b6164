#pragma once

#include <string>
#include <vector>

#include "sixdof_core/result.h"
#include "sixdof_core/trajectory.h"

namespace sixdof_core {

struct TimeParameterizationOptions {
  // Per joint, in the order of the joint names; all > 0 and finite.
  std::vector<double> max_velocity;
  std::vector<double> max_acceleration;
  // MoveIt's scaling factors: 0 < f <= 1, anything else is rejected.
  double velocity_scaling = 1.0;
  double acceleration_scaling = 1.0;
  // How far (joint-space norm, rad) the path may cut an interior waypoint with a circular blend.
  // 0 stops at every corner. Straight-through waypoints are never blended nor stopped at.
  double max_deviation = 0.01;
  // Time between output points (s).
  double sample_period = 0.01;
  // Longest grid step along the blends (joint-space arc length, rad) of the phase-plane solution; a step also
  // turns the path's tangent by at most 0.02 rad.
  double path_resolution = 1e-2;
};

enum class TimeParameterizationStatus { kSuccess, kInvalidInput, kNotConverged };

struct TimeParameterizationResult : Result<TimeParameterizationStatus> {
  Trajectory trajectory;
};

// Time-optimal parameterization along a path with circular blends (the path of Kunz & Stilman,
// "Time-optimal trajectory generation for path following with bounded acceleration and velocity",
// RSS 2012). The phase plane (path speed squared over arc length) is solved on a grid by a backward
// pass of maximal deceleration and a forward pass of maximal acceleration. A straight segment is one
// interval solved in closed form (full acceleration, cruise at its speed limit, full deceleration: exact);
// a blend is split into equal steps no longer than path_resolution nor turning by more than 0.02 rad, each
// with a constant path acceleration chosen so that every joint's velocity and acceleration limit holds at both
// ends of the step (within the grid's curvature error, which a 0.1% margin on the limits absorbs). The output
// starts and ends at rest, passes through the first and last waypoints exactly, stops exactly at waypoints
// where the path reverses or max_deviation is 0, and stays within max_deviation of every other waypoint.
// Positions are C1 along the path, velocities are continuous, accelerations are piecewise continuous
// (bang-bang, as any time-optimal profile).
TimeParameterizationResult computeTimeOptimalTrajectory(const std::vector<std::string>& joint_names,
                                                        const std::vector<std::vector<double>>& waypoints,
                                                        const TimeParameterizationOptions& options);

// Iterative parabolic parameterization (MoveIt's IterativeParabolicTimeParameterization scheme, moveit_commander's
// retime_trajectory default): one output point per waypoint, at rest at the first and last. Each segment first gets
// the shortest duration its velocity limits allow; then, pass after pass, every segment whose acceleration (from the
// velocity at its start to the one at its end, interior velocities being the mean of the adjacent segments') exceeds
// a limit is stretched, until none does (kNotConverged after 1000 passes). Repeated waypoints take 1 us.
// max_deviation, sample_period and path_resolution are checked but not used.
TimeParameterizationResult computeIterativeParabolicTrajectory(const std::vector<std::string>& joint_names,
                                                               const std::vector<std::vector<double>>& waypoints,
                                                               const TimeParameterizationOptions& options);

}  // namespace sixdof_core
