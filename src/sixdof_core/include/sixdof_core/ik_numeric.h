#pragma once

#include <string>

#include "sixdof_core/ik_solver.h"

namespace sixdof_core {

// General solver for any chain: Levenberg-Marquardt on the pose error. Joint limits: a revolute joint
// past a limit first tries the 2*pi-equivalent angle, else is clamped; joints resting on a limit that
// the step pushes outward are held (active set). Restarts from the seed, then random configurations,
// until the budget is spent.
class NumericIkSolver : public IkSolver {
 public:
  // Iterations of one start before it counts as stalled (4 times more once within 1 mm / 1 mrad).
  static constexpr int kMaxIterationsPerStart = 40;

  explicit NumericIkSolver(KinematicChain chain);
  std::string name() const override { return "numeric"; }

 protected:
  IkResult solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                          const Eigen::VectorXd& seed) const override;
};

}  // namespace sixdof_core
