#include "sixdof_core/ik_numeric.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "ik_common.h"

namespace sixdof_core {

namespace {

// A revolute joint past a limit is first turned by 2*pi (the same pose) if that lands within the
// limits, so a solver crossing +-pi on a joint with a range of about 2*pi is not stopped there;
// otherwise it is clamped.
void projectIntoLimits(const KinematicChain& chain, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                       Eigen::VectorXd* q) {
  for (Eigen::Index i = 0; i < q->size(); ++i) {
    double& v = (*q)[i];
    if (chain.joint(i).type != JointType::kPrismatic) {
      if (v > upper[i] && v - 2.0 * M_PI >= lower[i]) v -= 2.0 * M_PI;
      if (v < lower[i] && v + 2.0 * M_PI <= upper[i]) v += 2.0 * M_PI;
    }
    v = std::min(std::max(v, lower[i]), upper[i]);
  }
}

}  // namespace

NumericIkSolver::NumericIkSolver(KinematicChain chain) : IkSolver(std::move(chain)) {}

IkResult NumericIkSolver::solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                                         const Eigen::VectorXd& seed) const {
  const size_t n = chain_.dof();
  const int rows = options.position_only ? 3 : 6;
  Eigen::VectorXd lower(n), upper(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& limits = chain_.joint(i).limits;
    lower[i] = limits.bounded ? limits.lower : -std::numeric_limits<double>::infinity();
    upper[i] = limits.bounded ? limits.upper : std::numeric_limits<double>::infinity();
  }
  auto converged = [&](const Eigen::Matrix<double, 6, 1>& e) {
    return e.head<3>().norm() < options.epsilon && (options.position_only || e.tail<3>().norm() < options.epsilon);
  };

  std::mt19937_64 rng(options.random_seed);
  ik_detail::Budget budget(options);
  IkResult result;
  Eigen::Isometry3d tip;
  Matrix6Xd jacobian;
  bool out_of_time = false;
  while (!out_of_time && budget.nextAttempt()) {
    Eigen::VectorXd q = budget.used() == 1 ? seed.cwiseMax(lower).cwiseMin(upper).eval()
                                           : ik_detail::randomConfiguration(chain_, rng);
    chain_.forwardAndJacobian(q, &tip, &jacobian);
    Eigen::Matrix<double, 6, 1> e = ik_detail::twistError(tip, target);
    double cost = e.head(rows).squaredNorm();
    // Levenberg-Marquardt damping: small steps far from a solution, Gauss-Newton near it.
    double lambda = 1e-3;
    for (int it = 0; it < kMaxIterationsPerStart; ++it) {
      if (converged(e)) {
        ik_detail::wrapContinuous(chain_, seed, &q);
        result.status = IkStatus::kSuccess;
        result.solution = q;
        result.attempts = budget.used();
        ik_detail::setErrors(chain_, target, q, &result);
        if (options.position_only) result.orientation_error = 0.0;
        return result;
      }
      if (budget.expired()) {
        out_of_time = true;
        break;
      }
      ++result.iterations;
      const auto j = jacobian.topRows(rows);
      Eigen::MatrixXd a = j.transpose() * j;
      const Eigen::VectorXd g = j.transpose() * e.head(rows);
      a.diagonal().array() += lambda;
      Eigen::VectorXd q_new = q + a.ldlt().solve(g);
      projectIntoLimits(chain_, lower, upper, &q_new);
      Eigen::Isometry3d tip_new;
      Matrix6Xd jacobian_new;
      chain_.forwardAndJacobian(q_new, &tip_new, &jacobian_new);
      const Eigen::Matrix<double, 6, 1> e_new = ik_detail::twistError(tip_new, target);
      const double cost_new = e_new.head(rows).squaredNorm();
      if (cost_new < cost) {
        q = q_new;
        e = e_new;
        cost = cost_new;
        tip = tip_new;
        jacobian = jacobian_new;
        lambda = std::max(lambda * 0.1, 1e-12);
      } else {
        lambda *= 10.0;
        // A projected step that cannot reduce the error even when tiny: a local minimum or a limit.
        if (lambda > 1e6) break;
      }
    }
  }
  result.status = out_of_time ? IkStatus::kTimeout : budget.exhaustedStatus();
  result.attempts = budget.used();
  result.message = std::string("numeric IK found no solution (") + toString(result.status) + " after " +
                   std::to_string(budget.used()) + " starts)";
  return result;
}

}  // namespace sixdof_core
