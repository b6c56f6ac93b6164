#include "sixdof_core/ik_numeric.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
  // Joints that cannot pass a limit by turning 2*pi (see projectIntoLimits).
  std::vector<bool> can_hold(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& joint = chain_.joint(i);
    can_hold[i] = joint.limits.bounded &&
                  (joint.type == JointType::kPrismatic || joint.limits.upper - joint.limits.lower < 2.0 * M_PI - 1e-6);
  }
  auto converged = [&](const Eigen::Matrix<double, 6, 1>& e) {
    return e.head<3>().norm() < options.epsilon && (options.position_only || e.tail<3>().norm() < options.epsilon);
  };

  std::mt19937_64 rng(options.random_seed);
  ik_detail::Budget budget(options);
  IkResult result;
  // Buffers reused by every iteration (no allocation in the loop).
  Eigen::Isometry3d tip, tip_new;
  Matrix6Xd jacobian(6, n), jacobian_new(6, n);
  Eigen::MatrixXd a(n, n);
  Eigen::VectorXd g(n), g_held(n), step(n), q_new(n);
  Eigen::LDLT<Eigen::MatrixXd> ldlt(n);
  bool out_of_time = false;
  while (!out_of_time && budget.nextAttempt()) {
    Eigen::VectorXd q = budget.used() == 1 ? seed.cwiseMax(lower).cwiseMin(upper).eval()
                                           : ik_detail::randomConfiguration(chain_, rng);
    chain_.forwardAndJacobian(q, &tip, &jacobian);
    Eigen::Matrix<double, 6, 1> e = ik_detail::twistError(tip, target);
    double cost = e.head(rows).squaredNorm();
    // Levenberg-Marquardt damping: small steps far from a solution, Gauss-Newton near it.
    double lambda = 1e-3;
    // Close to a solution (error below 1 mm / 1 mrad) a start keeps going for longer: near singular
    // configurations Levenberg-Marquardt converges only linearly, and a restart would lose that progress.
    for (int it = 0; it < kMaxIterationsPerStart || (cost < 1e-6 && it < 4 * kMaxIterationsPerStart); ++it) {
      if (converged(e)) {
        ik_detail::setSuccess(chain_, seed, target, options, budget.used(), q, &result);
        return result;
      }
      if (budget.expired()) {
        out_of_time = true;
        break;
      }
      ++result.iterations;
      const auto j = jacobian.topRows(rows);
      a.noalias() = j.transpose() * j;
      g.noalias() = j.transpose() * e.head(rows);
      a.diagonal().array() += lambda;
      step = ldlt.compute(a).solve(g);
      // Active set: a joint resting on a limit that the step pushes further out is held there and
      // the others solve without it, instead of losing that part of the step to clamping.
      bool held = false;
      g_held = g;
      for (size_t i = 0; i < n; ++i) {
        if (can_hold[i] && ((q[i] <= lower[i] && step[i] < 0.0) || (q[i] >= upper[i] && step[i] > 0.0))) {
          a.row(i).setZero();
          a.col(i).setZero();
          a(i, i) = 1.0;
          g_held[i] = 0.0;
          held = true;
        }
      }
      if (held) step = ldlt.compute(a).solve(g_held);
      q_new = q + step;
      projectIntoLimits(chain_, lower, upper, &q_new);
      chain_.forwardAndJacobian(q_new, &tip_new, &jacobian_new);
      const Eigen::Matrix<double, 6, 1> e_new = ik_detail::twistError(tip_new, target);
      const double cost_new = e_new.head(rows).squaredNorm();
      if (cost_new < cost) {
        q.swap(q_new);
        e = e_new;
        cost = cost_new;
        tip = tip_new;
        jacobian.swap(jacobian_new);
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
