#include "sixdof_core/control/interpolation.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sixdof_sim {

JointTrajectory::JointTrajectory(std::vector<double> times, std::vector<TrajectoryPoint> knots)
    : times_(std::move(times)), knots_(std::move(knots)) {
  if (knots_.empty() || knots_.size() != times_.size()) {
    throw std::invalid_argument("JointTrajectory: needs at least one knot and one time per knot");
  }
  dof_ = knots_.front().positions.size();
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    const TrajectoryPoint& k = knots_[i];
    const bool sizes_ok = k.positions.size() == dof_ && (k.velocities.empty() || k.velocities.size() == dof_) &&
                          (k.accelerations.empty() || k.accelerations.size() == dof_);
    if (!sizes_ok) {
      throw std::invalid_argument("JointTrajectory: knot " + std::to_string(i) + " has inconsistent sizes");
    }
    if (i > 0 && !(times_[i] > times_[i - 1])) {
      throw std::invalid_argument("JointTrajectory: knot times must be strictly increasing (knot " +
                                  std::to_string(i) + ")");
    }
  }
  for (std::size_t s = 0; s + 1 < knots_.size(); ++s) {
    const TrajectoryPoint& a = knots_[s];
    const TrajectoryPoint& b = knots_[s + 1];
    const InterpolationType type = interpolationType(a, b);
    const auto at = [](const std::vector<double>& v, std::size_t j) { return v.empty() ? 0.0 : v[j]; };
    std::vector<JointSpline> joints;
    joints.reserve(dof_);
    for (std::size_t j = 0; j < dof_; ++j) {
      joints.emplace_back(type, times_[s + 1] - times_[s], a.positions[j], at(a.velocities, j),
                          at(a.accelerations, j), b.positions[j], at(b.velocities, j), at(b.accelerations, j));
    }
    types_.push_back(type);
    splines_.push_back(std::move(joints));
  }
}

TrajectorySample JointTrajectory::sample(double time) const {
  TrajectorySample out;
  out.position.resize(dof_);
  out.velocity.assign(dof_, 0.0);
  out.acceleration.assign(dof_, 0.0);
  if (time < times_.front() || time >= times_.back()) {
    out.position = time < times_.front() ? knots_.front().positions : knots_.back().positions;
    return out;
  }
  // Segment s spans [times_[s], times_[s + 1]).
  const auto it = std::upper_bound(times_.begin(), times_.end(), time);
  const std::size_t s = static_cast<std::size_t>(it - times_.begin()) - 1;
  for (std::size_t j = 0; j < dof_; ++j) {
    splines_[s][j].sample(time - times_[s], out.position[j], out.velocity[j], out.acceleration[j]);
  }
  return out;
}

}  // namespace sixdof_sim
