#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/result.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_core {

enum class IkStatus {
  kSuccess,
  kNoSolution,    // the attempt budget ran out without a solution
  kTimeout,       // the time budget ran out without a solution
  kOutOfReach,    // (analytic) the position is beyond the arm's reach
  kJointLimits,   // (analytic) solutions exist, but every one violates a joint limit
  kInvalidInput,  // NaN/non-rigid pose, bad seed, inconsistent options
};
const char* toString(IkStatus status);

struct IkOptions {
  // Time budget in seconds; <= 0 means none (then attempts must be > 0).
  double timeout = 0.005;
  // Maximum number of starts (the seed first, then random ones); 0 means until the timeout.
  // The analytic solver needs a single start for full-pose goals.
  int attempts = 0;
  // Convergence: position error (m) and, unless position_only, rotation error (rad).
  double epsilon = 1e-5;
  bool position_only = false;
  // Start configuration (chain dof() values); empty means the middle of the joint ranges.
  Eigen::VectorXd seed;
  // Random restarts are drawn from this seed, so results are reproducible.
  std::uint64_t random_seed = 42;
};

// status, message (why it failed), ok(): see Result.
struct IkResult : Result<IkStatus> {
  Eigen::VectorXd solution;        // chain joint values (set on success)
  double position_error = 0.0;     // of the returned (or best found) configuration, m
  double orientation_error = 0.0;  // rad
  int iterations = 0;              // solver iterations summed over attempts
  int attempts = 0;                // starts used
};

// Inverse kinematics of one group chain: the tip pose is given in the chain's base frame.
// solve() is const and keeps no state between calls, so one solver may serve several threads.
class IkSolver {
 public:
  explicit IkSolver(KinematicChain chain) : chain_(std::move(chain)) {}
  virtual ~IkSolver() = default;

  virtual std::string name() const = 0;
  const KinematicChain& chain() const { return chain_; }
  IkResult solve(const Eigen::Isometry3d& tip_in_base, const IkOptions& options = IkOptions()) const;
  // Same, from a position and a quaternion; a quaternion whose norm is not 1 (+-1e-6) is invalid input.
  IkResult solve(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                 const IkOptions& options = IkOptions()) const;

 protected:
  // Called with validated input: a rigid finite target and a seed of the right size.
  virtual IkResult solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                                  const Eigen::VectorXd& seed) const = 0;

  KinematicChain chain_;
};

// Builds the solver named in kinematics.yaml ("kdl", "analytic" or "numeric") for a group.
// Throws std::invalid_argument for an unknown solver name, RobotModelError for an unknown or
// non-chain group, and AnalyticIkUnsupported when the analytic solver does not fit the geometry.
std::unique_ptr<IkSolver> createIkSolver(const std::string& solver_name, const RobotModel& model,
                                         const std::string& group);

}  // namespace sixdof_core
