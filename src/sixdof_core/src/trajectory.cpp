#include "sixdof_core/trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sixdof_core {
namespace {

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Position, velocity and acceleration of the quintic (or lower-order) polynomial that matches the
// boundary states of one segment of duration T, at time tau in [0, T].
void interpolate(double q0, double v0, double a0, double q1, double v1, double a1, double T, double tau,
                 int order, double* q, double* v, double* a) {
  if (order == 1) {
    const double slope = (q1 - q0) / T;
    *q = q0 + slope * tau;
    *v = slope;
    *a = 0.0;
    return;
  }
  double c[6] = {q0, v0, 0.0, 0.0, 0.0, 0.0};
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  if (order == 3) {
    c[2] = (3.0 * (q1 - q0) - (2.0 * v0 + v1) * T) / T2;
    c[3] = (2.0 * (q0 - q1) + (v0 + v1) * T) / T3;
  } else {
    c[2] = 0.5 * a0;
    c[3] = (20.0 * (q1 - q0) - (8.0 * v1 + 12.0 * v0) * T - (3.0 * a0 - a1) * T2) / (2.0 * T3);
    c[4] = (30.0 * (q0 - q1) + (14.0 * v1 + 16.0 * v0) * T + (3.0 * a0 - 2.0 * a1) * T2) / (2.0 * T4);
    c[5] = (12.0 * (q1 - q0) - 6.0 * (v1 + v0) * T - (a0 - a1) * T2) / (2.0 * T5);
  }
  const double t = tau;
  *q = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
  *v = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
  *a = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
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
  const int order = !p0.accelerations.empty() ? 5 : (!p0.velocities.empty() ? 3 : 1);
  const double T = p1.time_from_start - p0.time_from_start;
  const double tau = time - p0.time_from_start;
  TrajectoryPoint& out = sample.point;
  out.time_from_start = time;
  out.positions.resize(n);
  out.velocities.resize(n);
  out.accelerations.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double v0 = order >= 3 ? p0.velocities[j] : 0.0, v1 = order >= 3 ? p1.velocities[j] : 0.0;
    const double a0 = order == 5 ? p0.accelerations[j] : 0.0, a1 = order == 5 ? p1.accelerations[j] : 0.0;
    interpolate(p0.positions[j], v0, a0, p1.positions[j], v1, a1, T, tau, order, &out.positions[j],
                &out.velocities[j], &out.accelerations[j]);
  }
  return sample;
}

}  // namespace sixdof_core
