#include "sixdof_core/cartesian_path.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace sixdof_core {
namespace {

bool finitePose(const Eigen::Isometry3d& pose) { return pose.matrix().allFinite(); }

std::string validateRequest(const CartesianPathRequest& r) {
  if (r.start.size() == 0) return "start state is empty";
  if (!r.start.allFinite()) return "start state contains NaN or infinite values";
  if (r.waypoints.empty()) return "no waypoints given";
  for (std::size_t k = 0; k < r.waypoints.size(); ++k) {
    if (!finitePose(r.waypoints[k])) return "waypoint " + std::to_string(k) + " contains NaN or infinite values";
  }
  if (!std::isfinite(r.eef_step) || r.eef_step <= 0.0) {
    return "eef_step must be > 0 (got " + std::to_string(r.eef_step) + ")";
  }
  if (!std::isfinite(r.eef_rotation_step) || r.eef_rotation_step < 0.0) {
    return "eef_rotation_step must be >= 0 (got " + std::to_string(r.eef_rotation_step) + ")";
  }
  const JumpThreshold& j = r.jump_threshold;
  for (double v : {j.relative, j.revolute, j.prismatic}) {
    if (!std::isfinite(v) || v < 0.0) return "jump thresholds must be >= 0";
  }
  if (!r.prismatic.empty() && static_cast<Eigen::Index>(r.prismatic.size()) != r.start.size()) {
    return "prismatic has " + std::to_string(r.prismatic.size()) + " flags for " + std::to_string(r.start.size()) +
           " joints";
  }
  if (!r.fk) return "no forward kinematics function given";
  if (!r.ik) return "no IK function given";
  if (r.avoid_collisions && !r.is_valid) return "avoid_collisions needs a state validity function";
  return "";
}

std::string explain(const CartesianPathRequest& r, const Eigen::VectorXd& q) {
  if (!r.explain_invalid) return "";
  const std::string why = r.explain_invalid(q);
  return why.empty() ? "" : ": " + why;
}

// Index of the first point reached by a jump (1..size-1), or 0 if none.
std::size_t firstAbsoluteJump(const CartesianPathRequest& r, const std::vector<Eigen::VectorXd>& path) {
  const JumpThreshold& j = r.jump_threshold;
  if (j.revolute <= 0.0 && j.prismatic <= 0.0) return 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    for (Eigen::Index i = 0; i < path[k].size(); ++i) {
      const bool prismatic = !r.prismatic.empty() && r.prismatic[i];
      const double limit = prismatic ? j.prismatic : j.revolute;
      if (limit > 0.0 && std::abs(path[k][i] - path[k - 1][i]) > limit) return k;
    }
  }
  return 0;
}

std::size_t firstRelativeJump(double factor, const std::vector<Eigen::VectorXd>& path) {
  std::vector<double> steps;
  double total = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    steps.push_back((path[k] - path[k - 1]).cwiseAbs().sum());
    total += steps.back();
  }
  const double limit = factor * total / static_cast<double>(steps.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (steps[k] > limit) return k + 1;
  }
  return 0;
}

}  // namespace

const char* toString(CartesianStatus status) {
  static constexpr const char* kNames[] = {"SUCCESS",   "INVALID_REQUEST", "INVALID_START",
                                           "IK_FAILED", "IN_COLLISION",    "JUMP_DETECTED"};
  return enumName<CartesianStatus::kJumpDetected>(status, kNames);
}

CartesianPathResult computeCartesianPath(const CartesianPathRequest& r) {
  CartesianPathResult result;
  const std::string invalid = validateRequest(r);
  if (!invalid.empty()) {
    result.fail(CartesianStatus::kInvalidRequest, invalid);
    return result;
  }
  if (r.avoid_collisions && !r.is_valid(r.start)) {
    result.status = CartesianStatus::kInvalidStart;
    result.message = "start state is invalid" + explain(r, r.start);
    return result;
  }

  result.status = CartesianStatus::kSuccess;
  result.path.push_back(r.start);
  std::vector<double> progress{0.0};  // fraction reached at each path point
  const double segments = static_cast<double>(r.waypoints.size());
  Eigen::Isometry3d from = r.fk(r.start);
  if (!finitePose(from)) {
    result.status = CartesianStatus::kInvalidRequest;
    result.message = "forward kinematics of the start state is not finite";
    result.path.clear();
    return result;
  }
  for (std::size_t w = 0; w < r.waypoints.size() && result.status == CartesianStatus::kSuccess; ++w) {
    const Eigen::Isometry3d& to = r.waypoints[w];
    const Eigen::Quaterniond q_from(from.linear());
    const Eigen::Quaterniond q_to(to.linear());
    const double distance = (to.translation() - from.translation()).norm();
    const double angle = q_from.angularDistance(q_to);
    // The small epsilon keeps exact multiples of the step from adding a needless extra point.
    double steps = std::max(1.0, std::ceil(distance / r.eef_step - 1e-9));
    if (r.eef_rotation_step > 0.0) steps = std::max(steps, std::ceil(angle / r.eef_rotation_step - 1e-9));
    const int n = static_cast<int>(steps);
    for (int s = 1; s <= n; ++s) {
      const double t = static_cast<double>(s) / n;
      Eigen::Isometry3d pose = to;
      if (s < n) {
        pose.linear() = q_from.slerp(t, q_to).toRotationMatrix();
        pose.translation() = from.translation() + t * (to.translation() - from.translation());
      }
      Eigen::VectorXd q;
      if (!r.ik(pose, result.path.back(), &q)) {
        std::ostringstream msg;
        msg << "IK failed at waypoint " << w << ", step " << s << "/" << n << " (tip at "
            << pose.translation().transpose() << ")";
        result.status = CartesianStatus::kIkFailed;
        result.message = msg.str();
        break;
      }
      if (q.size() != r.start.size() || !q.allFinite()) {
        result.status = CartesianStatus::kInvalidRequest;
        result.message = "IK function returned a malformed joint state (size " + std::to_string(q.size()) + ")";
        result.path.clear();
        return result;
      }
      if (r.avoid_collisions && !r.is_valid(q)) {
        result.status = CartesianStatus::kInCollision;
        result.message = "state at waypoint " + std::to_string(w) + ", step " + std::to_string(s) + "/" +
                         std::to_string(n) + " is invalid" + explain(r, q);
        break;
      }
      result.path.push_back(q);
      progress.push_back((static_cast<double>(w) + t) / segments);
    }
    from = to;
  }

  std::size_t cut = firstAbsoluteJump(r, result.path);
  std::string jump_kind = "absolute";
  if (r.jump_threshold.relative > 0.0) {
    if (result.path.size() < kMinPointsForRelativeJumpTest) {
      result.message += std::string(result.message.empty() ? "" : "; ") + "relative jump test skipped: only " +
                        std::to_string(result.path.size()) + " points (needs " +
                        std::to_string(kMinPointsForRelativeJumpTest) + ")";
    } else {
      const std::size_t relative_cut = firstRelativeJump(r.jump_threshold.relative, result.path);
      if (relative_cut != 0 && (cut == 0 || relative_cut < cut)) {
        cut = relative_cut;
        jump_kind = "relative";
      }
    }
  }
  if (cut != 0) {
    std::ostringstream msg;
    msg << "joint-space jump (" << jump_kind << " threshold) between points " << cut - 1 << " and " << cut
        << "; path cut there";
    result.status = CartesianStatus::kJumpDetected;
    result.message = msg.str();
    result.path.resize(cut);
    progress.resize(cut);
  }
  result.fraction = progress.back();
  return result;
}

CartesianPathResult computeCartesianPath(const Eigen::VectorXd& start, const std::vector<Eigen::Isometry3d>& waypoints,
                                         double eef_step, const JumpThreshold& jump_threshold, bool avoid_collisions,
                                         const TipFkFn& fk, const SeededIkFn& ik, const JointValidityFn& is_valid) {
  CartesianPathRequest request;
  request.start = start;
  request.waypoints = waypoints;
  request.eef_step = eef_step;
  request.jump_threshold = jump_threshold;
  request.avoid_collisions = avoid_collisions;
  request.fk = fk;
  request.ik = ik;
  request.is_valid = is_valid;
  return computeCartesianPath(request);
}

}  // namespace sixdof_core
