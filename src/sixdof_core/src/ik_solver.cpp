#include "sixdof_core/ik_solver.h"

#include <cmath>
#include <stdexcept>

#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/ik_kdl.h"
#include "sixdof_core/ik_numeric.h"

namespace sixdof_core {

namespace {

IkResult invalid(const std::string& message) {
  IkResult result;
  result.status = IkStatus::kInvalidInput;
  result.message = message;
  return result;
}

}  // namespace

const char* toString(IkStatus status) {
  static constexpr const char* kNames[] = {"success",      "no solution",  "timeout",
                                           "out of reach", "joint limits", "invalid input"};
  return enumName<IkStatus::kInvalidInput>(status, kNames, "unknown");
}

IkResult IkSolver::solve(const Eigen::Isometry3d& tip_in_base, const IkOptions& options) const {
  if (!tip_in_base.matrix().allFinite()) return invalid("target pose is not finite");
  const Eigen::Matrix3d r = tip_in_base.linear();
  if (!(r.transpose() * r).isIdentity(1e-6) || r.determinant() < 0.0) {
    return invalid("target orientation is not a rotation matrix");
  }
  if (!std::isfinite(options.timeout) || !(options.epsilon > 0.0) || options.attempts < 0) {
    return invalid("options need a finite timeout, epsilon > 0 and attempts >= 0");
  }
  if (options.timeout <= 0.0 && options.attempts == 0) {
    return invalid("options set neither a timeout nor an attempt limit");
  }
  Eigen::VectorXd seed = options.seed;
  if (seed.size() == 0) {
    seed = chain_.midPositions();
  } else if (static_cast<size_t>(seed.size()) != chain_.dof()) {
    return invalid("seed has " + std::to_string(seed.size()) + " values, the chain " + std::to_string(chain_.dof()) +
                   " joints");
  } else if (!seed.allFinite()) {
    return invalid("seed is not finite");
  }
  return solveValidated(tip_in_base, options, seed);
}

IkResult IkSolver::solve(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                         const IkOptions& options) const {
  if (!position.allFinite() || !orientation.coeffs().allFinite()) return invalid("target pose is not finite");
  if (std::abs(orientation.norm() - 1.0) > 1e-6) {
    return invalid("target quaternion is not normalized (norm " + std::to_string(orientation.norm()) + ")");
  }
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = position;
  target.linear() = orientation.toRotationMatrix();
  return solve(target, options);
}

std::unique_ptr<IkSolver> createIkSolver(const std::string& solver_name, const RobotModel& model,
                                         const std::string& group) {
  if (solver_name != "kdl" && solver_name != "analytic" && solver_name != "numeric") {
    throw std::invalid_argument("unknown kinematics solver '" + solver_name + "' (known: kdl, analytic, numeric)");
  }
  KinematicChain chain = KinematicChain::forGroup(model, group);
  if (solver_name == "kdl") return std::make_unique<KdlIkSolver>(std::move(chain));
  if (solver_name == "analytic") return std::make_unique<AnalyticIkSolver>(std::move(chain));
  return std::make_unique<NumericIkSolver>(std::move(chain));
}

}  // namespace sixdof_core
