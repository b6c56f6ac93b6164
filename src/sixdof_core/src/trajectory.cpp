#include "sixdof_core/trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace sixdof_core {
namespace {

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Empty when the trajectory can be sampled, else the problem. `strict` adds validateTrajectory's rules: the same
// derivatives on every point, and times from 0.
std::string problem(const Trajectory& trajectory, bool strict) {
  const std::size_t n = trajectory.joint_names.size();
  if (n == 0) return "trajectory has no joint names";
  if (trajectory.points.empty()) return "trajectory has no points";
  const bool has_v = !trajectory.points.front().velocities.empty();
  const bool has_a = !trajectory.points.front().accelerations.empty();
  for (std::size_t i = 0; i < trajectory.points.size(); ++i) {
    const TrajectoryPoint& p = trajectory.points[i];
    const auto sized = [&](const std::vector<double>& v, bool required) {
      return strict ? v.size() == (required ? n : 0) : v.empty() || v.size() == n;
    };
    std::ostringstream where;
    where << "trajectory point " << i << ": ";
    if (p.positions.size() != n) return where.str() + "positions size differs from the joint names";
    if (!sized(p.velocities, has_v)) return where.str() + "velocities size is inconsistent";
    if (!sized(p.accelerations, has_a)) return where.str() + "accelerations size is inconsistent";
    if (!allFinite(p.positions) || !allFinite(p.velocities) || !allFinite(p.accelerations)) {
      return where.str() + "non-finite value";
    }
    if (!std::isfinite(p.time_from_start) || (strict && p.time_from_start < 0.0)) {
      return where.str() + (strict ? "time_from_start must be finite and >= 0" : "time_from_start must be finite");
    }
    if (i > 0 && !(p.time_from_start > trajectory.points[i - 1].time_from_start)) {
      return where.str() + "time_from_start is not strictly increasing";
    }
  }
  return "";
}

}  // namespace

std::string validateTrajectory(const Trajectory& trajectory) { return problem(trajectory, true); }

InterpolationType interpolationType(const TrajectoryPoint& from, const TrajectoryPoint& to) {
  if (from.velocities.empty() || to.velocities.empty()) return InterpolationType::kLinear;
  if (from.accelerations.empty() || to.accelerations.empty()) return InterpolationType::kCubic;
  return InterpolationType::kQuintic;
}

TrajectorySampler::TrajectorySampler(Trajectory trajectory) : trajectory_(std::move(trajectory)) {
  const std::string invalid = problem(trajectory_, false);
  if (!invalid.empty()) {
    throw std::invalid_argument("TrajectorySampler: " + invalid);
  }
  dof_ = trajectory_.joint_names.size();
  const auto at = [](const std::vector<double>& v, std::size_t j) { return v.empty() ? 0.0 : v[j]; };
  const std::vector<TrajectoryPoint>& points = trajectory_.points;
  for (std::size_t s = 0; s + 1 < points.size(); ++s) {
    const TrajectoryPoint& a = points[s];
    const TrajectoryPoint& b = points[s + 1];
    const InterpolationType type = interpolationType(a, b);
    std::vector<JointSpline> joints;
    joints.reserve(dof_);
    for (std::size_t j = 0; j < dof_; ++j) {
      joints.emplace_back(type, b.time_from_start - a.time_from_start, a.positions[j], at(a.velocities, j),
                          at(a.accelerations, j), b.positions[j], at(b.velocities, j), at(b.accelerations, j));
    }
    types_.push_back(type);
    splines_.push_back(std::move(joints));
  }
}

TrajectorySampler::TrajectorySampler(Trajectory trajectory, std::vector<double> lower, std::vector<double> upper)
    : TrajectorySampler(std::move(trajectory)) {
  if (lower.size() != dof_ || upper.size() != dof_) {
    throw std::invalid_argument("TrajectorySampler: position bounds need one lower and one upper value per joint");
  }
  for (std::size_t j = 0; j < dof_; ++j) {
    if (!(lower[j] <= upper[j])) {
      throw std::invalid_argument("TrajectorySampler: position bounds of joint '" + trajectory_.joint_names[j] +
                                  "' are not ordered (lower <= upper)");
    }
  }
  lower_ = std::move(lower);
  upper_ = std::move(upper);
}

TrajectorySample TrajectorySampler::sample(double time) const {
  if (!std::isfinite(time)) {
    throw std::invalid_argument("TrajectorySampler: sample time must be finite");
  }
  const std::vector<TrajectoryPoint>& points = trajectory_.points;
  TrajectorySample out;
  out.velocity.assign(dof_, 0.0);
  out.acceleration.assign(dof_, 0.0);
  if (time < startTime() || time > endTime()) {
    out.position = time < startTime() ? points.front().positions : points.back().positions;
    return out;
  }
  // The first point strictly later than `time`; none when `time` is the last point's.
  const auto it = std::upper_bound(points.begin(), points.end(), time,
                                   [](double t, const TrajectoryPoint& p) { return t < p.time_from_start; });
  if (it == points.end()) {
    const TrajectoryPoint& last = points.back();
    out.position = last.positions;
    if (!last.velocities.empty()) out.velocity = last.velocities;
    if (!last.accelerations.empty()) out.acceleration = last.accelerations;
    return out;
  }
  const std::size_t s = static_cast<std::size_t>(it - points.begin()) - 1;
  out.position.resize(dof_);
  for (std::size_t j = 0; j < dof_; ++j) {
    splines_[s][j].sample(time - points[s].time_from_start, out.position[j], out.velocity[j], out.acceleration[j]);
  }
  if (lower_.empty()) return out;
  const auto within = [&](std::size_t point, std::size_t j) {
    return points[point].positions[j] >= lower_[j] && points[point].positions[j] <= upper_[j];
  };
  for (std::size_t j = 0; j < dof_; ++j) {
    const double bounded = std::clamp(out.position[j], lower_[j], upper_[j]);
    if (bounded != out.position[j] && within(s, j) && within(s + 1, j)) {
      out.position[j] = bounded;
      out.velocity[j] = 0.0;
      out.acceleration[j] = 0.0;
    }
  }
  return out;
}

}  // namespace sixdof_core
