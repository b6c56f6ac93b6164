#include "request.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

#include <ompl/util/RandomNumbers.h>

namespace sixdof_core {
namespace detail {

namespace {

// Goal states closer than this (joint distance) are the same state.
constexpr double kDuplicateGoalDistance = 1e-9;
// Random states tried inside a joint goal's tolerance box when the target itself is invalid.
constexpr int kToleranceSamples = 100;
constexpr int kMaxToleranceGoals = 8;

bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

GoalSet fail(PlanningStatus status, std::string message) {
  GoalSet g;
  g.fail(status, std::move(message));
  return g;
}

bool distinct(const std::vector<JointBounds>& joints, const Eigen::VectorXd& q,
              const std::vector<Eigen::VectorXd>& states) {
  for (const Eigen::VectorXd& s : states) {
    if (jointDistance(joints, s, q) < kDuplicateGoalDistance) return false;
  }
  return true;
}

void addDistinct(const std::vector<JointBounds>& joints, const Eigen::VectorXd& q, std::vector<Eigen::VectorXd>* out) {
  if (distinct(joints, q, *out)) out->push_back(q);
}

}  // namespace

std::string formatState(const Eigen::VectorXd& q) {
  std::ostringstream out;
  out << "[";
  for (Eigen::Index i = 0; i < q.size(); ++i) out << (i ? ", " : "") << q[i];
  out << "]";
  return out.str();
}

// Returns an error message naming the first joint out of bounds, or "" if q is within bounds.
std::string boundsViolation(const std::vector<JointBounds>& joints, const Eigen::VectorXd& q) {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const JointBounds& j = joints[i];
    if (!j.continuous && (q[i] < j.lower || q[i] > j.upper)) {
      std::ostringstream out;
      out << j.name << " = " << q[i] << " is outside its bounds [" << j.lower << ", " << j.upper << "]";
      return out.str();
    }
  }
  return "";
}

// Returns "" or why a vector cannot be a joint state of this problem.
std::string shapeError(std::size_t n, const Eigen::VectorXd& q) {
  if (static_cast<std::size_t>(q.size()) != n) {
    return "has " + std::to_string(q.size()) + " values for " + std::to_string(n) + " joints";
  }
  if (!q.allFinite()) return "contains NaN or infinite values " + formatState(q);
  return "";
}


std::string validateOptions(const PlanningOptions& o) {
  if (!std::isfinite(o.allowed_planning_time) || o.allowed_planning_time <= 0.0) {
    return "allowed_planning_time must be > 0 (got " + std::to_string(o.allowed_planning_time) + ")";
  }
  if (o.num_planning_attempts < 1) {
    return "num_planning_attempts must be >= 1 (got " + std::to_string(o.num_planning_attempts) + ")";
  }
  if (!std::isfinite(o.longest_valid_segment_fraction) || o.longest_valid_segment_fraction <= 0.0 ||
      o.longest_valid_segment_fraction > 1.0) {
    return "longest_valid_segment_fraction must be in (0, 1] (got " +
           std::to_string(o.longest_valid_segment_fraction) + ")";
  }
  if (!finiteNonNegative(o.longest_valid_segment_length)) {
    return "longest_valid_segment_length must be >= 0 (got " + std::to_string(o.longest_valid_segment_length) + ")";
  }
  if (!finiteNonNegative(o.max_joint_step)) {
    return "max_joint_step must be >= 0 (got " + std::to_string(o.max_joint_step) + ")";
  }
  if (!std::isfinite(o.simplify_coarse_factor) || o.simplify_coarse_factor < 1.0) {
    return "simplify_coarse_factor must be >= 1 (got " + std::to_string(o.simplify_coarse_factor) + ")";
  }
  return "";
}

std::string validateJoints(const std::vector<JointBounds>& joints) {
  if (joints.empty()) return "the problem has no joints";
  std::set<std::string> names;
  for (const JointBounds& j : joints) {
    if (j.name.empty()) return "a joint has an empty name";
    if (!names.insert(j.name).second) return "joint " + j.name + " is listed twice";
    if (!j.continuous && !(std::isfinite(j.lower) && std::isfinite(j.upper) && j.lower <= j.upper)) {
      std::ostringstream out;
      out << "joint " << j.name << " has invalid bounds [" << j.lower << ", " << j.upper << "]";
      return out.str();
    }
  }
  return "";
}

GoalSet jointGoalStates(const PlanningProblem& p, Session* session) {
  const std::size_t n = p.joints.size();
  const JointGoal& goal = *p.joint_goal;
  std::string err = shapeError(n, goal.target);
  if (!err.empty()) return fail(PlanningStatus::kInvalidRequest, "joint goal target " + err);
  Eigen::VectorXd tolerance = goal.tolerance.size() == 0 ? Eigen::VectorXd::Zero(n) : goal.tolerance;
  err = shapeError(n, tolerance);
  if (!err.empty()) return fail(PlanningStatus::kInvalidRequest, "joint goal tolerance " + err);
  if ((tolerance.array() < 0.0).any()) {
    return fail(PlanningStatus::kInvalidRequest, "joint goal tolerance is negative: " + formatState(tolerance));
  }
  err = boundsViolation(p.joints, goal.target);
  if (!err.empty()) return fail(PlanningStatus::kInvalidGoal, "joint goal: " + err);
  GoalSet set;
  if (session->valid(goal.target)) {
    set.states.push_back(goal.target);
    return set;
  }
  if ((tolerance.array() > 0.0).any()) {
    ompl::RNG rng;
    for (int k = 0; k < kToleranceSamples && static_cast<int>(set.states.size()) < kMaxToleranceGoals; ++k) {
      Eigen::VectorXd q(n);
      for (std::size_t i = 0; i < n; ++i) {
        double lo = goal.target[i] - tolerance[i];
        double hi = goal.target[i] + tolerance[i];
        if (!p.joints[i].continuous) {
          lo = std::max(lo, p.joints[i].lower);
          hi = std::min(hi, p.joints[i].upper);
        }
        q[i] = rng.uniformReal(lo, hi);
      }
      if (session->valid(q)) addDistinct(p.joints, q, &set.states);
    }
  }
  if (set.states.empty()) {
    return fail(PlanningStatus::kGoalInCollision,
                "joint goal " + formatState(goal.target) + " is invalid" + session->reason(goal.target) +
                    ((tolerance.array() > 0.0).any() ? " (nor was any state sampled within its tolerance valid)" : ""));
  }
  return set;
}

GoalSet explicitGoalStates(const PlanningProblem& p, Session* session) {
  const std::size_t n = p.joints.size();
  for (std::size_t k = 0; k < p.goal_states.size(); ++k) {
    std::string err = shapeError(n, p.goal_states[k]);
    if (!err.empty()) return fail(PlanningStatus::kInvalidRequest, "goal state " + std::to_string(k) + " " + err);
    err = boundsViolation(p.joints, p.goal_states[k]);
    if (!err.empty()) return fail(PlanningStatus::kInvalidGoal, "goal state " + std::to_string(k) + ": " + err);
  }
  GoalSet set;
  for (const Eigen::VectorXd& q : p.goal_states) {
    if (session->valid(q)) addDistinct(p.joints, q, &set.states);
  }
  if (set.states.empty()) {
    return fail(PlanningStatus::kGoalInCollision, "all " + std::to_string(p.goal_states.size()) +
                                                      " goal states are invalid (first" +
                                                      session->reason(p.goal_states.front()) + ")");
  }
  return set;
}

GoalSet sampledGoalStates(const PlanningProblem& p, Session* session) {
  const SampledGoal& goal = *p.sampled_goal;
  if (!goal.sampler) return fail(PlanningStatus::kInvalidRequest, "sampled goal has no sampler function");
  if (goal.max_states < 1 || goal.max_calls < 1) {
    return fail(PlanningStatus::kInvalidRequest, "sampled goal needs max_states >= 1 and max_calls >= 1");
  }
  const std::size_t n = p.joints.size();
  GoalSet set;
  std::vector<Eigen::VectorXd> rejected;
  int produced = 0;
  std::string first_reason;
  for (int call = 0; call < goal.max_calls && static_cast<int>(set.states.size()) < goal.max_states; ++call) {
    Eigen::VectorXd q;
    if (!goal.sampler(&q)) continue;
    ++produced;
    std::string err = shapeError(n, q);
    if (!err.empty()) return fail(PlanningStatus::kInvalidRequest, "goal sampler returned a state that " + err);
    err = boundsViolation(p.joints, q);
    if (!err.empty()) return fail(PlanningStatus::kInvalidGoal, "goal sampler returned a state where " + err);
    // The sampler (IK from random seeds) often returns a state it returned before: its validity is known.
    if (!distinct(p.joints, q, set.states) || !distinct(p.joints, q, rejected)) continue;
    if (session->valid(q)) {
      set.states.push_back(q);
    } else {
      rejected.push_back(q);
      if (produced == 1) first_reason = session->reason(q);
    }
  }
  if (produced == 0) {
    return fail(PlanningStatus::kNoIkSolution,
                "goal sampler produced no state in " + std::to_string(goal.max_calls) + " calls");
  }
  if (set.states.empty()) {
    return fail(PlanningStatus::kGoalInCollision, "all " + std::to_string(produced) +
                                                      " sampled goal states are invalid (first" + first_reason + ")");
  }
  return set;
}

}  // namespace detail
}  // namespace sixdof_core
