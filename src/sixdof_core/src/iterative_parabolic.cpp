// Iterative parabolic time parameterization: retime a path point by point (time_parameterization.h).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sixdof_core/time_parameterization.h"
#include "time_parameterization_inputs.h"

namespace sixdof_core {
namespace {

constexpr int kMaxPasses = 1000;
// s: the shortest segment, so that a repeated waypoint still takes a positive time.
constexpr double kShortestSegment = 1e-6;
// A segment is stretched by a little more than the square root of its acceleration ratio, so that passes end.
constexpr double kStretchMargin = 1.0001;
constexpr double kRatioTolerance = 1e-9;

// The velocity at every point: at rest at both ends, inside the mean of the adjacent segments' velocities.
Eigen::MatrixXd pointVelocities(const Eigen::MatrixXd& deltas, const Eigen::VectorXd& durations) {
  const Eigen::Index count = deltas.rows() + 1;
  Eigen::MatrixXd velocities = Eigen::MatrixXd::Zero(count, deltas.cols());
  for (Eigen::Index i = 1; i + 1 < count; ++i) {
    velocities.row(i) = 0.5 * (deltas.row(i - 1) / durations[i - 1] + deltas.row(i) / durations[i]);
  }
  return velocities;
}

// The largest ratio of |change| / duration to its limit over the joints.
double limitRatio(const Eigen::RowVectorXd& change, double duration, const Eigen::RowVectorXd& limit) {
  return (change.cwiseAbs().cwiseQuotient(limit)).maxCoeff() / duration;
}

std::vector<double> values(const Eigen::RowVectorXd& row) { return std::vector<double>(row.begin(), row.end()); }

}  // namespace

TimeParameterizationResult computeIterativeParabolicTrajectory(const std::vector<std::string>& joint_names,
                                                               const std::vector<std::vector<double>>& waypoints,
                                                               const TimeParameterizationOptions& options) {
  if (auto rejected = rejectInvalidInput(joint_names, waypoints, options)) return *rejected;
  const auto count = static_cast<Eigen::Index>(waypoints.size());
  const auto n = static_cast<Eigen::Index>(joint_names.size());
  Eigen::MatrixXd path(count, n);
  for (Eigen::Index i = 0; i < count; ++i) path.row(i) = Eigen::Map<const Eigen::RowVectorXd>(waypoints[i].data(), n);
  const Eigen::RowVectorXd max_velocity =
      Eigen::Map<const Eigen::RowVectorXd>(options.max_velocity.data(), n) * options.velocity_scaling;
  const Eigen::RowVectorXd max_acceleration =
      Eigen::Map<const Eigen::RowVectorXd>(options.max_acceleration.data(), n) * options.acceleration_scaling;

  const Eigen::MatrixXd deltas = path.bottomRows(count - 1) - path.topRows(count - 1);
  Eigen::VectorXd durations(count - 1);
  for (Eigen::Index i = 0; i + 1 < count; ++i) {
    durations[i] = std::max(kShortestSegment, limitRatio(deltas.row(i), 1.0, max_velocity));
  }
  bool settled = count == 1;
  for (int pass = 0; pass < kMaxPasses && !settled; ++pass) {
    const Eigen::MatrixXd velocities = pointVelocities(deltas, durations);
    settled = true;
    for (Eigen::Index i = 0; i + 1 < count; ++i) {
      const double ratio = limitRatio(velocities.row(i + 1) - velocities.row(i), durations[i], max_acceleration);
      if (ratio > 1.0 + kRatioTolerance) {
        durations[i] *= std::sqrt(ratio) * kStretchMargin;
        settled = false;
      }
    }
  }
  TimeParameterizationResult result;
  if (!settled) {
    result.fail(TimeParameterizationStatus::kNotConverged,
                "time parameterization: the accelerations did not settle within the limits after " +
                    std::to_string(kMaxPasses) + " passes");
    return result;
  }

  const Eigen::MatrixXd velocities = pointVelocities(deltas, durations);
  Eigen::VectorXd times = Eigen::VectorXd::Zero(count);
  for (Eigen::Index i = 1; i < count; ++i) times[i] = times[i - 1] + durations[i - 1];
  Eigen::MatrixXd accelerations = Eigen::MatrixXd::Zero(count, n);
  if (count > 1) {
    // Central differences inside, one-sided at the ends.
    for (Eigen::Index i = 1; i + 1 < count; ++i) {
      accelerations.row(i) = (velocities.row(i + 1) - velocities.row(i - 1)) / (times[i + 1] - times[i - 1]);
    }
    accelerations.row(0) = (velocities.row(1) - velocities.row(0)) / durations[0];
    accelerations.row(count - 1) = (velocities.row(count - 1) - velocities.row(count - 2)) / durations[count - 2];
  }
  result.trajectory.joint_names = joint_names;
  for (Eigen::Index i = 0; i < count; ++i) {
    TrajectoryPoint point;
    point.positions = waypoints[i];
    point.velocities = values(velocities.row(i));
    point.accelerations = values(accelerations.row(i));
    point.time_from_start = times[i];
    result.trajectory.points.push_back(std::move(point));
  }
  return result;
}

}  // namespace sixdof_core
