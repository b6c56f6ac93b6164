#include "sixdof_core/ik_analytic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ik_common.h"

namespace sixdof_core {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Tolerances of the closed form: geometry checks at construction, and how far past the reach
// boundary rounding may push an argument of acos before the target counts as unreachable.
constexpr double kGeometryTolerance = 1e-6;
constexpr double kParallelTolerance = 1e-9;
constexpr double kBoundaryTolerance = 1e-9;
// Inexact geometry (see kCandidateTolerance) can push a reachable target this far past a boundary.
constexpr double kNearBoundary = 1e-4;
// A URDF whose wrist axes meet only to rounding (rpy written as 1.5708, CAD exports) makes the closed
// form slightly inexact: candidates within kCandidateTolerance (m, rad) of the target get a few Newton
// steps on the exact kinematics until within kExactTolerance; others are dropped.
constexpr double kCandidateTolerance = 1e-3;
constexpr double kExactTolerance = 1e-10;
constexpr int kRefineIterations = 8;

double normalizeAngle(double a) { return std::remainder(a, 2.0 * M_PI); }

Eigen::Vector3d perpendicular(const Eigen::Vector3d& w, const Eigen::Vector3d& v) { return v - w * w.dot(v); }

double distanceToLine(const Eigen::Vector3d& x, const Eigen::Vector3d& w, const Eigen::Vector3d& p) {
  return perpendicular(w, x - p).norm();
}

// Paden-Kahan subproblem 1: the angle about unit w (through the origin) taking u's component
// perpendicular to w onto v's. False when u has no perpendicular component (the angle is free).
bool rotationAngle(const Eigen::Vector3d& w, const Eigen::Vector3d& u, const Eigen::Vector3d& v, double* angle) {
  const Eigen::Vector3d up = perpendicular(w, u);
  const Eigen::Vector3d vp = perpendicular(w, v);
  if (up.norm() < 1e-12 || vp.norm() < 1e-12) return false;
  *angle = std::atan2(w.dot(up.cross(vp)), up.dot(vp));
  return true;
}

// a*cos(x) + b*sin(x) = c: 0, 1 or 2 solutions appended to xs; false when there are none.
// `free_value` is used when a = b = 0 and c = 0 (every x solves it). Slightly past the boundary
// (|c/r| - 1 < kNearBoundary) the boundary solution is returned for refinement and *near is set.
bool solveTrig(double a, double b, double c, double free_value, double* xs, int* count, bool* near) {
  const double r = std::hypot(a, b);
  if (r < 1e-12) {
    if (std::abs(c) > kBoundaryTolerance) return false;
    xs[(*count)++] = free_value;
    return true;
  }
  double ratio = c / r;
  if (std::abs(ratio) > 1.0 + kNearBoundary) return false;
  if (std::abs(ratio) > 1.0 + kBoundaryTolerance) *near = true;
  ratio = std::max(-1.0, std::min(1.0, ratio));
  const double base = std::atan2(b, a);
  const double offset = std::acos(ratio);
  xs[(*count)++] = base + offset;
  if (offset > 1e-12) xs[(*count)++] = base - offset;
  return true;
}

Eigen::Matrix3d rot(const Eigen::Vector3d& w, double angle) { return Eigen::AngleAxisd(angle, w).toRotationMatrix(); }

}  // namespace

AnalyticIkSolver::AnalyticIkSolver(KinematicChain chain) : IkSolver(std::move(chain)) {
  const std::string where = "analytic IK (chain " + chain_.baseLink() + " -> " + chain_.tipLink() + "): ";
  if (chain_.dof() != 6) {
    throw AnalyticIkUnsupported(where + "needs 6 joints, the chain has " + std::to_string(chain_.dof()));
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < 6; ++i) {
    if (chain_.joint(i).type == JointType::kPrismatic) {
      throw AnalyticIkUnsupported(where + "joint '" + chain_.joint(i).name + "' is prismatic; all must be revolute");
    }
    t = t * chain_.jointOffset(i);
    w_[i] = (t.linear() * chain_.joint(i).axis).normalized();
    p_[i] = t.translation();
  }
  home_ = chain_.forward(Eigen::VectorXd::Zero(6));
  const auto& names = chain_.jointNames();
  auto parallel = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.cross(b).norm() < kParallelTolerance;
  };
  if (parallel(w_[0], w_[1])) {
    throw AnalyticIkUnsupported(where + "axes of '" + names[0] + "' and '" + names[1] + "' are parallel");
  }
  if (!parallel(w_[1], w_[2])) {
    throw AnalyticIkUnsupported(where + "axes of '" + names[1] + "' and '" + names[2] + "' are not parallel");
  }
  if (distanceToLine(p_[2], w_[1], p_[1]) < kGeometryTolerance) {
    throw AnalyticIkUnsupported(where + "axes of '" + names[1] + "' and '" + names[2] + "' coincide");
  }
  if (parallel(w_[3], w_[4]) || parallel(w_[4], w_[5])) {
    throw AnalyticIkUnsupported(where + "neighbouring wrist axes ('" + names[3] + "', '" + names[4] + "', '" +
                                names[5] + "') are parallel");
  }
  // The point nearest to the three wrist axes (least squares); a spherical wrist has them meet there.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i = 3; i < 6; ++i) {
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - w_[i] * w_[i].transpose();
    a += projector;
    b += projector * p_[i];
  }
  wrist_center_ = a.ldlt().solve(b);
  double worst = 0.0;
  for (int i = 3; i < 6; ++i) worst = std::max(worst, distanceToLine(wrist_center_, w_[i], p_[i]));
  if (worst > kGeometryTolerance) {
    std::ostringstream message;
    message << where << "not a spherical wrist: the axes of '" << names[3] << "', '" << names[4] << "', '" << names[5]
            << "' do not intersect (they miss a common point by " << worst << " m)";
    throw AnalyticIkUnsupported(message.str());
  }
  if (distanceToLine(wrist_center_, w_[2], p_[2]) < kGeometryTolerance) {
    throw AnalyticIkUnsupported(where + "the wrist centre lies on the axis of '" + names[2] + "'");
  }
}

void AnalyticIkSolver::forwardPoe(const Vector6d& q, Eigen::Isometry3d* tip) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) {
    const Eigen::Matrix3d r = rot(w_[i], q[i]);
    t.translation() += t.linear() * (p_[i] - r * p_[i]);
    t.linear() = t.linear() * r;
  }
  *tip = t * home_;
}

void AnalyticIkSolver::jacobianPoe(const Vector6d& q, const Eigen::Vector3d& tip, Matrix6d* jacobian) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d axis = t.linear() * w_[i];
    jacobian->block<3, 1>(0, i) = axis.cross(tip - t * p_[i]);
    jacobian->block<3, 1>(3, i) = axis;
    const Eigen::Matrix3d r = rot(w_[i], q[i]);
    t.translation() += t.linear() * (p_[i] - r * p_[i]);
    t.linear() = t.linear() * r;
  }
}

bool AnalyticIkSolver::refine(const Eigen::Isometry3d& target, Vector6d* q) const {
  Eigen::Isometry3d reached;
  Matrix6d jacobian;
  for (int it = 0;; ++it) {
    forwardPoe(*q, &reached);
    const Vector6d e = ik_detail::twistError(reached, target);
    const double position = e.head<3>().norm();
    const double orientation = e.tail<3>().norm();
    if (position < kExactTolerance && orientation < kExactTolerance) return true;
    // Far off: a spurious candidate, not a slightly inexact one.
    if (it == kRefineIterations || position > kCandidateTolerance || orientation > kCandidateTolerance) return false;
    jacobianPoe(*q, reached.translation(), &jacobian);
    *q += (jacobian.transpose() * jacobian + 1e-12 * Matrix6d::Identity()).ldlt().solve(jacobian.transpose() * e);
  }
}

IkStatus AnalyticIkSolver::solveRaw(const Eigen::Isometry3d& target, const Vector6d& seed, Candidates* out,
                                    std::string* message) const {
  out->count = 0;
  // The wrist joints do not move the wrist centre, so the first three joints alone must bring it there.
  const Eigen::Vector3d center = target * (home_.inverse() * wrist_center_);

  // Joint 1: rotations about the parallel axes 2 and 3 keep the wrist centre's coordinate along w2,
  // which fixes the rotation about axis 1: w2 . (p1 + R1(-q1) v) = w2 . c.
  const Eigen::Vector3d v = center - p_[0];
  const double along1 = w_[0].dot(v);
  double q1s[2];
  int n1 = 0;
  bool near_boundary = false;
  if (!solveTrig(w_[1].dot(v - w_[0] * along1), w_[1].dot(w_[0].cross(v)),
                 w_[1].dot(wrist_center_ - p_[0]) - along1 * w_[1].dot(w_[0]), -seed[0], q1s, &n1,
                 &near_boundary)) {
    *message = "target is out of reach (no rotation of the first joint brings the wrist centre into the arm plane)";
    return IkStatus::kOutOfReach;
  }
  bool arm_reachable = false;
  for (int i1 = 0; i1 < n1; ++i1) {
    const double q1 = normalizeAngle(-q1s[i1]);
    const Eigen::Matrix3d r1 = rot(w_[0], q1);
    // The wrist centre as joints 2 and 3 alone must place it.
    const Eigen::Vector3d p = p_[0] + r1.transpose() * v;

    // Joint 3: its rotation alone sets the distance from axis 2 to the wrist centre (subproblem 3).
    const Eigen::Vector3d u = wrist_center_ - p_[2];
    const Eigen::Vector3d to2 = p_[1] - p_[2];
    const Eigen::Vector3d up = perpendicular(w_[2], u);
    const Eigen::Vector3d vp = perpendicular(w_[2], to2);
    const double axial = w_[2].dot(u - to2);
    const double delta_sq = (p - p_[1]).squaredNorm() - axial * axial;
    double q3s[2];
    int n3 = 0;
    bool near3 = near_boundary;
    // |up|^2 + |vp|^2 - 2 |up||vp| cos(theta0 - q3) = delta_sq
    const double theta0 = std::atan2(w_[2].dot(up.cross(vp)), up.dot(vp));
    if (!solveTrig(2.0 * up.norm() * vp.norm(), 0.0, up.squaredNorm() + vp.squaredNorm() - delta_sq, 0.0, q3s,
                   &n3, &near3)) {
      continue;
    }
    arm_reachable = arm_reachable || !near3;
    for (int i3 = 0; i3 < n3; ++i3) {
      const double q3 = normalizeAngle(theta0 - q3s[i3]);
      const Eigen::Matrix3d r3 = rot(w_[2], q3);
      const Eigen::Vector3d x = p_[2] + r3 * u;
      double q2 = seed[1];
      // Joint 2 rotates the placed wrist centre onto p (free only if the centre is on axis 2).
      rotationAngle(w_[1], x - p_[1], p - p_[1], &q2);
      q2 = normalizeAngle(q2);
      const Eigen::Matrix3d r123 = r1 * rot(w_[1], q2) * r3;
      const Eigen::Matrix3d rw = r123.transpose() * target.linear() * home_.linear().transpose();

      // Joints 4 and 5 point axis 6 where rw points it (subproblem 2); joint 6 then sets the roll.
      const Eigen::Vector3d from = w_[5];
      const Eigen::Vector3d to = rw * w_[5];
      const double k = w_[3].dot(w_[4]);
      const double den = 1.0 - k * k;
      const double alpha = (w_[3].dot(to) - k * w_[4].dot(from)) / den;
      const double beta = (w_[4].dot(from) - k * w_[3].dot(to)) / den;
      const Eigen::Vector3d cross45 = w_[3].cross(w_[4]);
      const double gamma_sq = (1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * k) / cross45.squaredNorm();
      if (gamma_sq < -kNearBoundary) continue;
      const double gamma = std::sqrt(std::max(0.0, gamma_sq));
      const int n_gamma = gamma > 1e-12 ? 2 : 1;
      for (int ig = 0; ig < n_gamma; ++ig) {
        const Eigen::Vector3d c = alpha * w_[3] + beta * w_[4] + (ig == 0 ? gamma : -gamma) * cross45;
        double q5 = 0.0;
        rotationAngle(w_[4], from, c, &q5);
        double q4 = seed[3];
        // Free at the wrist singularity (axis 6 along axis 4): keep the seed's joint 4.
        rotationAngle(w_[3], c, to, &q4);
        q4 = normalizeAngle(q4);
        const Eigen::Matrix3d r6 = (rot(w_[3], q4) * rot(w_[4], q5)).transpose() * rw;
        const Eigen::Vector3d any = w_[5].unitOrthogonal();
        double q6 = 0.0;
        rotationAngle(w_[5], any, r6 * any, &q6);
        out->q[out->count++] << q1, q2, q3, q4, q5, q6;
      }
    }
  }
  out->arm_reachable = arm_reachable;
  if (out->count > 0) return IkStatus::kSuccess;
  if (!arm_reachable) {
    *message = "target is out of reach (the wrist centre is beyond the arm's reach)";
    return IkStatus::kOutOfReach;
  }
  *message = "target orientation is not reachable by the wrist";
  return IkStatus::kNoSolution;
}

IkStatus AnalyticIkSolver::refinementFailure(const Candidates& candidates, std::string* message) {
  if (!candidates.arm_reachable) {
    *message = "target is out of reach (the wrist centre is beyond the arm's reach)";
    return IkStatus::kOutOfReach;
  }
  *message = "no closed-form candidate converges to the target (numerical failure)";
  return IkStatus::kNoSolution;
}

namespace {

// Calls f for every variant of q within limits: bounded multi-turn joints add 2*pi multiples,
// continuous joints take the multiple nearest the seed. False when no variant is within limits.
template <typename F>
bool forEachWithinLimits(const KinematicChain& chain, const Vector6d& q, const Vector6d& seed, F&& f) {
  double values[6][4];
  int counts[6];
  for (int i = 0; i < 6; ++i) {
    const JointModel& joint = chain.joint(i);
    counts[i] = 0;
    if (!joint.limits.bounded) {
      values[i][counts[i]++] = q[i] + 2.0 * M_PI * std::round((seed[i] - q[i]) / (2.0 * M_PI));
      continue;
    }
    const double first = std::ceil((joint.limits.lower - q[i]) / (2.0 * M_PI));
    const double last = std::floor((joint.limits.upper - q[i]) / (2.0 * M_PI));
    for (double k = first; k <= last && counts[i] < 4; k += 1.0) values[i][counts[i]++] = q[i] + 2.0 * M_PI * k;
    if (counts[i] == 0) return false;
  }
  Vector6d variant;
  int index[6] = {0, 0, 0, 0, 0, 0};
  while (true) {
    for (int i = 0; i < 6; ++i) variant[i] = values[i][index[i]];
    f(variant);
    int i = 5;
    while (i >= 0 && ++index[i] == counts[i]) index[i--] = 0;
    if (i < 0) return true;
  }
}

}  // namespace

AnalyticSolutions AnalyticIkSolver::solveAll(const Eigen::Isometry3d& tip_in_base, const Eigen::VectorXd& seed) const {
  AnalyticSolutions all;
  const Vector6d s = seed.size() == 6 ? Vector6d(seed) : Vector6d::Zero();
  Candidates candidates;
  all.status = solveRaw(tip_in_base, s, &candidates, &all.message);
  std::vector<Vector6d> exact;
  for (int c = 0; c < candidates.count; ++c) {
    Vector6d q = candidates.q[c];
    if (!refine(tip_in_base, &q)) continue;
    for (int i = 0; i < 6; ++i) q[i] = normalizeAngle(q[i]);
    bool duplicate = false;
    for (const auto& other : exact) duplicate = duplicate || (other - q).cwiseAbs().maxCoeff() < 1e-9;
    if (!duplicate) exact.push_back(q);
  }
  all.unconstrained_count = static_cast<int>(exact.size());
  if (candidates.count > 0 && exact.empty()) all.status = refinementFailure(candidates, &all.message);
  for (const auto& q : exact) {
    forEachWithinLimits(chain_, q, s, [&](const Vector6d& variant) { all.solutions.emplace_back(variant); });
  }
  if (!exact.empty() && all.solutions.empty()) {
    all.status = IkStatus::kJointLimits;
    all.message = std::to_string(exact.size()) + " solutions, each violating a joint limit";
  }
  return all;
}

IkStatus AnalyticIkSolver::solveNearest(const Eigen::Isometry3d& target, const Vector6d& seed, Vector6d* best,
                                        std::string* message) const {
  Candidates candidates;
  const IkStatus status = solveRaw(target, seed, &candidates, message);
  if (status != IkStatus::kSuccess) return status;
  // Only the chosen solution needs the (rarely needed) refinement: try candidates nearest-first, each
  // in its 2*pi variant nearest the seed.
  std::pair<double, int> order[8];
  Vector6d nearest[8];
  int within = 0;
  for (int c = 0; c < candidates.count; ++c) {
    double best_distance = std::numeric_limits<double>::infinity();
    forEachWithinLimits(chain_, candidates.q[c], seed, [&](const Vector6d& variant) {
      const double distance = (variant - seed).squaredNorm();
      if (distance < best_distance) {
        best_distance = distance;
        nearest[c] = variant;
      }
    });
    if (best_distance == std::numeric_limits<double>::infinity()) continue;
    // Insertion into the (at most 8) sorted entries.
    int k = within++;
    for (; k > 0 && order[k - 1].first > best_distance; --k) order[k] = order[k - 1];
    order[k] = {best_distance, c};
  }
  for (int k = 0; k < within; ++k) {
    Vector6d q = nearest[order[k].second];
    if (refine(target, &q) && chain_.withinLimits(q)) {
      *best = q;
      return IkStatus::kSuccess;
    }
  }
  if (within == 0) {
    *message = std::to_string(candidates.count) + " solutions, each violating a joint limit";
    return IkStatus::kJointLimits;
  }
  return refinementFailure(candidates, message);
}

IkResult AnalyticIkSolver::solveValidated(const Eigen::Isometry3d& target, const IkOptions& options,
                                          const Eigen::VectorXd& seed) const {
  const Vector6d s(seed);
  IkResult result;
  Vector6d best;
  if (!options.position_only) {
    result.attempts = 1;
    result.status = solveNearest(target, s, &best, &result.message);
    if (result.ok()) {
      result.solution = best;
      Eigen::Isometry3d reached;
      forwardPoe(best, &reached);
      const PoseError error = poseError(reached, target);
      result.position_error = error.position;
      result.orientation_error = error.orientation;
    }
    return result;
  }
  // Position-only goals: the seed's orientation first, then random orientations, until the budget ends.
  std::mt19937_64 rng(options.random_seed);
  ik_detail::Budget budget(options);
  Eigen::Isometry3d goal = target;
  goal.linear() = chain_.forward(seed).linear();
  while (budget.nextAttempt()) {
    if (budget.used() > 1) {
      Eigen::Vector4d random;
      std::normal_distribution<double> normal;
      for (int i = 0; i < 4; ++i) random[i] = normal(rng);
      goal.linear() = Eigen::Quaterniond(random.normalized()).toRotationMatrix();
    }
    if (solveNearest(goal, s, &best, &result.message) != IkStatus::kSuccess) continue;
    result.status = IkStatus::kSuccess;
    result.message.clear();
    result.solution = best;
    result.attempts = budget.used();
    ik_detail::setErrors(chain_, target, result.solution, &result);
    result.orientation_error = 0.0;
    return result;
  }
  result.status = budget.exhaustedStatus();
  result.attempts = budget.used();
  return result;
}

}  // namespace sixdof_core
