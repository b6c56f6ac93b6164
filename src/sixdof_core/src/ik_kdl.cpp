#include "sixdof_core/ik_kdl.h"

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include <cmath>
#include <limits>

#include <Eigen/SVD>

#include "ik_common.h"

namespace sixdof_core {

namespace {

KDL::Frame toKdl(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d& r = t.linear();
  return KDL::Frame(KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
                    KDL::Vector(t.translation().x(), t.translation().y(), t.translation().z()));
}

// One segment per joint, as kdl_parser builds it: the joint moves in the segment's root frame and the
// segment ends at the next joint's origin (the tip offset for the last one).
KDL::Chain toKdlChain(const KinematicChain& chain) {
  KDL::Chain kdl;
  kdl.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::None), toKdl(chain.jointOffset(0))));
  for (size_t i = 0; i < chain.dof(); ++i) {
    const JointModel& joint = chain.joint(i);
    const KDL::Vector axis(joint.axis.x(), joint.axis.y(), joint.axis.z());
    const auto type = joint.type == JointType::kPrismatic ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
    const Eigen::Isometry3d& next = i + 1 < chain.dof() ? chain.jointOffset(i + 1) : chain.tipOffset();
    kdl.addSegment(KDL::Segment(KDL::Joint(joint.name, KDL::Vector::Zero(), axis, type), toKdl(next)));
  }
  return kdl;
}

// Newton-Raphson on the position rows with the same clamping as NR_JL; true when converged.
bool solvePositionOnly(const KinematicChain& chain, const Eigen::Vector3d& target, double epsilon,
                       const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* q,
                       int* iterations) {
  Eigen::Isometry3d tip;
  Matrix6Xd jacobian;
  for (int i = 0; i < KdlIkSolver::kMaxIterations; ++i) {
    chain.forwardAndJacobian(*q, &tip, &jacobian);
    const Eigen::Vector3d error = target - tip.translation();
    if (error.norm() < epsilon) return true;
    ++*iterations;
    const Eigen::MatrixXd jp = jacobian.topRows<3>();
    *q += jp.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(error);
    *q = q->cwiseMax(lower).cwiseMin(upper);
  }
  return false;
}

}  // namespace

KdlIkSolver::KdlIkSolver(KinematicChain chain) : IkSolver(std::move(chain)) {}

IkResult KdlIkSolver::solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                                     const Eigen::VectorXd& seed) const {
  const size_t n = chain_.dof();
  // Unbounded joints get infinite limits, so NR_JL never clamps them.
  Eigen::VectorXd lower(n), upper(n);
  KDL::JntArray q_min(n), q_max(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& limits = chain_.joint(i).limits;
    lower[i] = limits.bounded ? limits.lower : std::numeric_limits<double>::lowest();
    upper[i] = limits.bounded ? limits.upper : std::numeric_limits<double>::max();
    q_min(i) = lower[i];
    q_max(i) = upper[i];
  }
  const KDL::Chain kdl_chain = toKdlChain(chain_);
  KDL::ChainFkSolverPos_recursive fk(kdl_chain);
  KDL::ChainIkSolverVel_pinv ik_vel(kdl_chain);
  // NR_JL compares each twist component with eps; eps / sqrt(3) bounds the position and rotation
  // error norms by epsilon, as for the other solvers.
  KDL::ChainIkSolverPos_NR_JL ik_pos(kdl_chain, q_min, q_max, fk, ik_vel, kMaxIterations,
                                     options.epsilon / std::sqrt(3.0));
  const KDL::Frame kdl_target = toKdl(target);

  std::mt19937_64 rng(options.random_seed);
  ik_detail::Budget budget(options);
  IkResult result;
  KDL::JntArray q_init(n), q_out(n);
  while (budget.nextAttempt()) {
    Eigen::VectorXd start = budget.used() == 1 ? seed : ik_detail::randomConfiguration(chain_, rng);
    bool converged = false;
    Eigen::VectorXd q(n);
    if (options.position_only) {
      q = start.cwiseMax(lower).cwiseMin(upper);
      converged = solvePositionOnly(chain_, target.translation(), options.epsilon, lower, upper, &q,
                                    &result.iterations);
    } else {
      q_init.data = start;
      converged = ik_pos.CartToJnt(q_init, kdl_target, q_out) >= 0;
      // NR_JL does not report its iteration count: a failed start used all of them, a converged one
      // is counted as one.
      result.iterations += converged ? 1 : kMaxIterations;
      q = q_out.data;
    }
    if (converged) {
      ik_detail::setSuccess(chain_, seed, target, options, budget.used(), q, &result);
      return result;
    }
  }
  result.status = budget.exhaustedStatus();
  result.attempts = budget.used();
  result.message = std::string("KDL NR_JL found no solution (") + toString(result.status) + " after " +
                   std::to_string(budget.used()) + " starts)";
  return result;
}

}  // namespace sixdof_core
