#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/ik_solver.h"

namespace sixdof_core {

// Thrown when a chain does not have the structure the closed-form solver needs.
class AnalyticIkUnsupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every solution of one target pose; ok() if any solution respects the limits.
struct AnalyticSolutions : Result<IkStatus> {
  std::vector<Eigen::VectorXd> solutions;  // within limits; bounded multi-turn joints add 2*pi multiples
  int unconstrained_count = 0;             // solutions before the joint-limit filter (up to 8)
};

// Closed-form inverse kinematics of a 6R arm with a spherical wrist, derived from the chain geometry
// at zero joint values (product-of-exponentials form): joint 1 from the wrist-centre height along
// joint 2's axis, joint 3 from the shoulder-to-wrist distance, joint 2 by a plane rotation, then the
// wrist from the remaining rotation. Needs: 6 revolute joints; axes 4, 5, 6 meeting in one point;
// axes 2 and 3 parallel and distinct; axis 1 not parallel to axis 2; wrist axes pairwise not parallel.
// Continuous joints are returned nearest the seed (solveAll: in [-pi, pi]). Geometry that meets the
// conditions only to rounding (1e-6 m) is accepted; Newton steps make its solutions exact.
class AnalyticIkSolver : public IkSolver {
 public:
  // Throws AnalyticIkUnsupported naming the violated condition.
  explicit AnalyticIkSolver(KinematicChain chain);
  std::string name() const override { return "analytic"; }

  // All solutions within limits. `seed` (dof() values or empty) only resolves free joints at
  // singular configurations and places continuous joints.
  AnalyticSolutions solveAll(const Eigen::Isometry3d& tip_in_base, const Eigen::VectorXd& seed = {}) const;

  const Eigen::Vector3d& wristCenter() const { return wrist_center_; }

 protected:
  IkResult solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                          const Eigen::VectorXd& seed) const override;

 private:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  // Closed-form candidates (up to 2 for joint 1 x 2 elbow x 2 wrist), before refinement.
  struct Candidates {
    Vector6d q[8];
    int count = 0;
    bool arm_reachable = false;  // reached without stretching past a boundary by rounding
  };
  IkStatus solveRaw(const Eigen::Isometry3d& target, const Vector6d& seed, Candidates* out,
                    std::string* message) const;
  // The solution within limits nearest the seed.
  IkStatus solveNearest(const Eigen::Isometry3d& target, const Vector6d& seed, Vector6d* best,
                        std::string* message) const;
  static IkStatus refinementFailure(const Candidates& candidates, std::string* message);
  // Exact kinematics in product-of-exponentials form (fixed-size, no allocation).
  void forwardPoe(const Vector6d& q, Eigen::Isometry3d* tip) const;
  void jacobianPoe(const Vector6d& q, const Eigen::Vector3d& tip, Matrix6d* jacobian) const;
  // Newton steps from a closed-form candidate; false if it is not (close to) a solution.
  bool refine(const Eigen::Isometry3d& target, Vector6d* q) const;

  // Joint axes (unit) and one point on each, in the base frame at zero joint values.
  Eigen::Vector3d w_[6];
  Eigen::Vector3d p_[6];
  Eigen::Vector3d wrist_center_;
  Eigen::Isometry3d home_ = Eigen::Isometry3d::Identity();  // tip pose at zero
};

}  // namespace sixdof_core
