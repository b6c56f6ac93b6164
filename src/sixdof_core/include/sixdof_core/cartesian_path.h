#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sixdof_core/planning.h"
#include "sixdof_core/result.h"

namespace sixdof_core {

// Cartesian (straight-line) paths of the tip, with MoveIt's computeCartesianPath semantics, on plain
// callbacks: forward kinematics of the tip, a seeded IK and the state validity function.

// Pose of the tip for a joint state (any fixed frame; the waypoints use the same frame).
using TipFkFn = std::function<Eigen::Isometry3d(const Eigen::VectorXd& joints)>;
// IK for a tip pose, seeded with (and expected to stay close to) the previous path point; false = no solution.
using SeededIkFn =
    std::function<bool(const Eigen::Isometry3d& target, const Eigen::VectorXd& seed, Eigen::VectorXd* out)>;

// Joint-space jump detection (a 0 disables the test). A jump truncates the path before it.
struct JumpThreshold {
  // MoveIt's jump_threshold: a step whose joint distance (sum of |delta|) exceeds relative x the mean step of
  // the path is a jump. Needs at least kMinPointsForRelativeJumpTest points (as MoveIt), else it is skipped
  // and the result message says so.
  double relative = 0.0;
  double revolute = 0.0;   // rad: any revolute joint moving more than this in one step is a jump
  double prismatic = 0.0;  // m: same for prismatic joints
};

constexpr std::size_t kMinPointsForRelativeJumpTest = 10;

enum class CartesianStatus {
  kSuccess,         // the whole path was achieved (fraction 1)
  kInvalidRequest,  // malformed request (message says what)
  kInvalidStart,    // start state invalid (avoid_collisions) - fraction 0, empty path
  kIkFailed,        // stopped before the first pose IK could not solve
  kInCollision,     // stopped before the first invalid state
  kJumpDetected,    // truncated before the first joint-space jump
};

const char* toString(CartesianStatus status);

struct CartesianPathRequest {
  Eigen::VectorXd start;
  std::vector<Eigen::Isometry3d> waypoints;  // tip poses to go through in order, starting from fk(start)
  double eef_step = 0.01;                    // m: largest tip translation between consecutive points (> 0)
  double eef_rotation_step = 0.0;            // rad: largest tip rotation between points; 0 = not limited
  JumpThreshold jump_threshold;
  bool avoid_collisions = true;  // check every point with is_valid
  std::vector<bool> prismatic;   // per joint, for the absolute jump test; empty = all revolute
  TipFkFn fk;
  SeededIkFn ik;
  JointValidityFn is_valid;                // required when avoid_collisions
  JointValidityExplainFn explain_invalid;  // optional, words the kInCollision / kInvalidStart message
};

// message: on failure what stopped the path; a success may carry a note (a skipped relative jump test).
struct CartesianPathResult : Result<CartesianStatus> {
  // Start state first, then one point per interpolated pose, up to where the path stopped.
  std::vector<Eigen::VectorXd> path;
  // Achieved part of the requested path: each waypoint segment counts 1 / waypoints.size(), the segment where
  // the path stopped counts the achieved share of its interpolation steps (MoveIt's definition).
  double fraction = 0.0;
};

// Interpolates the tip from fk(start) through the waypoints (position linearly, orientation by slerp) so that
// consecutive poses are at most eef_step (and eef_rotation_step) apart, solves each pose with IK seeded by the
// previous point, and stops at the first IK failure or invalid state; jumps are then cut off.
CartesianPathResult computeCartesianPath(const CartesianPathRequest& request);

// The same, with MoveIt's argument order.
CartesianPathResult computeCartesianPath(const Eigen::VectorXd& start, const std::vector<Eigen::Isometry3d>& waypoints,
                                         double eef_step, const JumpThreshold& jump_threshold, bool avoid_collisions,
                                         const TipFkFn& fk, const SeededIkFn& ik, const JointValidityFn& is_valid);

}  // namespace sixdof_core
