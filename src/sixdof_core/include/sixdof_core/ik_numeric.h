#pragma once

#include <string>

#include "sixdof_core/ik_solver.h"

namespace sixdof_core {

// General solver for any chain: Levenberg-Marquardt on the pose error with joint limits enforced by
// projection, restarted from random configurations when it stalls, until the budget is spent.
class NumericIkSolver : public IkSolver {
 public:
  // Iterations of one start before it counts as stalled.
  static constexpr int kMaxIterationsPerStart = 40;

  explicit NumericIkSolver(KinematicChain chain);
  std::string name() const override { return "numeric"; }

 protected:
  IkResult solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                          const Eigen::VectorXd& seed) const override;
};

}  // namespace sixdof_core
