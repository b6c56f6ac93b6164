#pragma once

#include <chrono>
#include <cmath>
#include <random>

#include "sixdof_core/ik_solver.h"

namespace sixdof_core {
namespace ik_detail {

// Attempt and time budget shared by the restarting solvers.
class Budget {
 public:
  explicit Budget(const IkOptions& options)
      : attempts_(options.attempts),
        has_deadline_(options.timeout > 0.0),
        deadline_(std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(options.timeout > 0.0 ? options.timeout : 0.0))) {}

  // Whether another start may begin; counts it.
  bool nextAttempt() {
    if (attempts_ > 0 && used_ >= attempts_) return false;
    if (used_ > 0 && expired()) return false;
    ++used_;
    return true;
  }
  bool expired() const { return has_deadline_ && std::chrono::steady_clock::now() >= deadline_; }
  int used() const { return used_; }
  // The failure status once the budget is spent.
  IkStatus exhaustedStatus() const {
    return (attempts_ > 0 && used_ >= attempts_) ? IkStatus::kNoSolution : IkStatus::kTimeout;
  }

 private:
  int attempts_;
  int used_ = 0;
  bool has_deadline_;
  std::chrono::steady_clock::time_point deadline_;
};

// Uniform random configuration within the chain's limits (continuous joints in [-pi, pi]).
inline Eigen::VectorXd randomConfiguration(const KinematicChain& chain, std::mt19937_64& rng) {
  Eigen::VectorXd q(chain.dof());
  for (size_t i = 0; i < chain.dof(); ++i) {
    const auto& limits = chain.joint(i).limits;
    q[i] = std::uniform_real_distribution<double>(limits.lower, limits.upper)(rng);
  }
  return q;
}

// Continuous joints wrapped to the 2*pi multiple nearest the reference.
inline void wrapContinuous(const KinematicChain& chain, const Eigen::VectorXd& reference, Eigen::VectorXd* q) {
  for (size_t i = 0; i < chain.dof(); ++i) {
    if (chain.joint(i).type == JointType::kContinuous) {
      (*q)[i] += 2.0 * M_PI * std::round((reference[i] - (*q)[i]) / (2.0 * M_PI));
    }
  }
}

// Position error and rotation vector (base frame) taking `current` to `target`.
inline Eigen::Matrix<double, 6, 1> twistError(const Eigen::Isometry3d& current, const Eigen::Isometry3d& target) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = target.translation() - current.translation();
  const Eigen::AngleAxisd rotation(target.linear() * current.linear().transpose());
  e.tail<3>() = rotation.angle() * rotation.axis();
  return e;
}

// Fills a result's errors from the configuration's actual pose.
inline void setErrors(const KinematicChain& chain, const Eigen::Isometry3d& target, const Eigen::VectorXd& q,
                      IkResult* result) {
  const PoseError error = poseError(chain.forward(q), target);
  result->position_error = error.position;
  result->orientation_error = error.orientation;
}

// Fills a result for a converged start: q wrapped next to the seed, kSuccess, the attempts used and the
// errors (no orientation error for a position-only goal).
inline void setSuccess(const KinematicChain& chain, const Eigen::VectorXd& seed, const Eigen::Isometry3d& target,
                       const IkOptions& options, int attempts, Eigen::VectorXd q, IkResult* result) {
  wrapContinuous(chain, seed, &q);
  result->status = IkStatus::kSuccess;
  result->solution = q;
  result->attempts = attempts;
  setErrors(chain, target, q, result);
  if (options.position_only) result->orientation_error = 0.0;
}

}  // namespace ik_detail
}  // namespace sixdof_core
