#include "sixdof_core/trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sixdof_core/spline.h"

namespace sixdof_core {
namespace {

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

std::string validateTrajectory(const Trajectory& trajectory) {
  const std::size_t n = trajectory.joint_names.size();
  if (n == 0) return "trajectory has no joint names";
  if (trajectory.points.empty()) return "trajectory has no points";
  const bool has_v = !trajectory.points.front().velocities.empty();
  const bool has_a = !trajectory.points.front().accelerations.empty();
  double last_time = -1.0;
  for (std::size_t i = 0; i < trajectory.points.size(); ++i) {
    const TrajectoryPoint& p = trajectory.points[i];
    std::ostringstream where;
    where << "trajectory point " << i << ": ";
    if (p.positions.size() != n) return where.str() + "positions size differs from the joint names";
    if (p.velocities.size() != (has_v ? n : 0)) return where.str() + "velocities size is inconsistent";
    if (p.accelerations.size() != (has_a ? n : 0)) return where.str() + "accelerations size is inconsistent";
    if (!allFinite(p.positions) || !allFinite(p.velocities) || !allFinite(p.accelerations)) {
      return where.str() + "non-finite value";
    }
    if (!std::isfinite(p.time_from_start) || p.time_from_start < 0.0) {
      return where.str() + "time_from_start must be finite and >= 0";
    }
    if (p.time_from_start <= last_time) return where.str() + "time_from_start is not strictly increasing";
    last_time = p.time_from_start;
  }
  return "";
}

TrajectorySample sampleTrajectory(const Trajectory& trajectory, double time) {
  TrajectorySample sample;
  const std::string invalid = validateTrajectory(trajectory);
  if (!invalid.empty()) {
    sample.message = invalid;
    return sample;
  }
  if (!std::isfinite(time) || time < 0.0 || time > trajectory.duration()) {
    std::ostringstream msg;
    msg << "sample time " << time << " outside [0, " << trajectory.duration() << "]";
    sample.message = msg.str();
    return sample;
  }
  const auto& points = trajectory.points;
  const std::size_t n = trajectory.joint_names.size();
  sample.ok = true;
  if (time <= points.front().time_from_start) {
    sample.point = points.front();
    sample.point.time_from_start = time;
    sample.point.velocities.assign(n, 0.0);
    sample.point.accelerations.assign(n, 0.0);
    if (points.size() == 1 || time == points.front().time_from_start) sample.point = points.front();
    return sample;
  }
  // First point strictly later than time; the segment is [hi - 1, hi].
  auto it = std::upper_bound(points.begin(), points.end(), time,
                             [](double t, const TrajectoryPoint& p) { return t < p.time_from_start; });
  if (it == points.end()) {
    sample.point = points.back();
    if (sample.point.velocities.empty()) sample.point.velocities.assign(n, 0.0);
    if (sample.point.accelerations.empty()) sample.point.accelerations.assign(n, 0.0);
    return sample;
  }
  const TrajectoryPoint& p1 = *it;
  const TrajectoryPoint& p0 = *(it - 1);
  const InterpolationType type = interpolationType(p0, p1);
  const double T = p1.time_from_start - p0.time_from_start;
  const double tau = time - p0.time_from_start;
  const auto at = [](const std::vector<double>& v, std::size_t j) { return v.empty() ? 0.0 : v[j]; };
  TrajectoryPoint& out = sample.point;
  out.time_from_start = time;
  out.positions.resize(n);
  out.velocities.resize(n);
  out.accelerations.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const JointSpline spline(type, T, p0.positions[j], at(p0.velocities, j), at(p0.accelerations, j),
                             p1.positions[j], at(p1.velocities, j), at(p1.accelerations, j));
    spline.sample(tau, out.positions[j], out.velocities[j], out.accelerations[j]);
  }
  return sample;
}

}  // namespace sixdof_core
