#pragma once

#include <string>

#include "sixdof_core/ik_solver.h"

namespace sixdof_core {

// MoveIt's default: KDL's Newton-Raphson solver with joint limits (ChainIkSolverPos_NR_JL, 500
// iterations, epsilon from the options as a bound on the error norms), restarted from random
// configurations until the budget is spent. Position-only goals run the same Newton-Raphson
// iteration on the position rows only.
class KdlIkSolver : public IkSolver {
 public:
  static constexpr int kMaxIterations = 500;

  explicit KdlIkSolver(KinematicChain chain);
  std::string name() const override { return "kdl"; }

 protected:
  IkResult solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                          const Eigen::VectorXd& seed) const override;
};

}  // namespace sixdof_core
