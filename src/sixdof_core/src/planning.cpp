#include "sixdof_core/planning.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/goals/GoalStates.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

namespace sixdof_core {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

using Clock = std::chrono::steady_clock;

constexpr double kTwoPi = 2.0 * M_PI;
// Goal states closer than this (joint distance) are the same state.
constexpr double kDuplicateGoalDistance = 1e-9;
// Random states tried inside a joint goal's tolerance box when the target itself is invalid.
constexpr int kToleranceSamples = 100;
constexpr int kMaxToleranceGoals = 8;
// The coarsest check resolution (fraction of the space's maximum extent) of the simplifier's coarse pass.
constexpr double kCoarsestSimplifyFraction = 0.005;
// KPIECE-style planners grid the projection (the first two joints, as MoveIt's default) in this many cells.
constexpr double kProjectionCellsPerJoint = 20.0;

double shortestAngle(double from, double to) {
  double d = std::fmod(to - from, kTwoPi);
  if (d > M_PI) d -= kTwoPi;
  if (d < -M_PI) d += kTwoPi;
  return d;
}

double jointDelta(const JointBounds& joint, double from, double to) {
  return joint.continuous ? shortestAngle(from, to) : to - from;
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string formatState(const Eigen::VectorXd& q) {
  std::ostringstream out;
  out << "[";
  for (Eigen::Index i = 0; i < q.size(); ++i) out << (i ? ", " : "") << q[i];
  out << "]";
  return out.str();
}

// Maps joint vectors to OMPL states: a RealVectorStateSpace for the bounded joints, plus one SO2 subspace per
// continuous joint (then all inside a CompoundStateSpace).
class JointSpace {
 public:
  explicit JointSpace(const std::vector<JointBounds>& joints) : joints_(joints), slot_(joints.size(), -1) {
    std::vector<std::size_t> bounded;
    std::vector<std::size_t> continuous;
    for (std::size_t i = 0; i < joints.size(); ++i) (joints[i].continuous ? continuous : bounded).push_back(i);
    std::shared_ptr<ob::RealVectorStateSpace> real;
    if (!bounded.empty()) {
      real = std::make_shared<ob::RealVectorStateSpace>(bounded.size());
      ob::RealVectorBounds bounds(bounded.size());
      for (std::size_t k = 0; k < bounded.size(); ++k) {
        bounds.setLow(k, joints[bounded[k]].lower);
        bounds.setHigh(k, joints[bounded[k]].upper);
        real->setDimensionName(k, joints[bounded[k]].name);
        slot_[bounded[k]] = static_cast<int>(k);
      }
      real->setBounds(bounds);
    }
    if (continuous.empty()) {
      space_ = real;
      return;
    }
    compound_ = true;
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    if (real) compound->addSubspace(real, 1.0);
    for (std::size_t i : continuous) {
      slot_[i] = static_cast<int>(compound->getSubspaceCount());
      compound->addSubspace(std::make_shared<ob::SO2StateSpace>(), 1.0);
    }
    compound->lock();
    space_ = compound;
  }

  const ob::StateSpacePtr& space() const { return space_; }
  const std::vector<JointBounds>& joints() const { return joints_; }

  double& value(ob::State* state, std::size_t joint) const {
    if (!compound_) return state->as<ob::RealVectorStateSpace::StateType>()->values[slot_[joint]];
    auto* compound = state->as<ob::CompoundState>();
    if (joints_[joint].continuous) return compound->as<ob::SO2StateSpace::StateType>(slot_[joint])->value;
    return compound->as<ob::RealVectorStateSpace::StateType>(0)->values[slot_[joint]];
  }

  double value(const ob::State* state, std::size_t joint) const {
    return value(const_cast<ob::State*>(state), joint);
  }

  void toOmpl(const Eigen::VectorXd& q, ob::State* state) const {
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      value(state, i) = joints_[i].continuous ? std::remainder(q[i], kTwoPi) : q[i];
    }
  }

  Eigen::VectorXd fromOmpl(const ob::State* state) const {
    Eigen::VectorXd q(joints_.size());
    for (std::size_t i = 0; i < joints_.size(); ++i) q[i] = value(state, i);
    return q;
  }

 private:
  std::vector<JointBounds> joints_;
  std::vector<int> slot_;  // index in the real vector, or the SO2 subspace index
  bool compound_ = false;
  ob::StateSpacePtr space_;
};

// Projection on the first (up to) two joints for the grid-based planners (KPIECE, SBL, EST).
class FirstJointsProjection : public ob::ProjectionEvaluator {
 public:
  // The state space owns its projections, so this holds a plain pointer (a shared one would be a cycle).
  explicit FirstJointsProjection(const JointSpace* joint_space)
      : ob::ProjectionEvaluator(joint_space->space()), joint_space_(joint_space) {
    std::vector<double> cells;
    for (unsigned int i = 0; i < getDimension(); ++i) {
      const JointBounds& joint = joint_space_->joints()[i];
      const double extent = joint.continuous ? kTwoPi : joint.upper - joint.lower;
      cells.push_back(std::max(extent, 1e-6) / kProjectionCellsPerJoint);
    }
    // Set here so the state space's own default projection does not replace this one in setup().
    setCellSizes(cells);
  }

  unsigned int getDimension() const override {
    return static_cast<unsigned int>(std::min<std::size_t>(2, joint_space_->joints().size()));
  }

  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    for (unsigned int i = 0; i < getDimension(); ++i) projection[i] = joint_space_->value(state, i);
  }

 private:
  const JointSpace* joint_space_;
};

class CallbackValidityChecker : public ob::StateValidityChecker {
 public:
  CallbackValidityChecker(const ob::SpaceInformationPtr& si, std::shared_ptr<const JointSpace> joint_space,
                          std::function<bool(const Eigen::VectorXd&)> check)
      : ob::StateValidityChecker(si), joint_space_(std::move(joint_space)), check_(std::move(check)) {}

  bool isValid(const ob::State* state) const override {
    return si_->satisfiesBounds(state) && check_(joint_space_->fromOmpl(state));
  }

 private:
  std::shared_ptr<const JointSpace> joint_space_;
  std::function<bool(const Eigen::VectorXd&)> check_;
};

using PlannerFactory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

template <typename T>
ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si) {
  return std::make_shared<T>(si);
}

const std::map<std::string, PlannerFactory>& plannerFactories() {
  static const std::map<std::string, PlannerFactory> factories = {
      {"BiEST", makePlanner<og::BiEST>},         {"BiTRRT", makePlanner<og::BiTRRT>},
      {"BKPIECE1", makePlanner<og::BKPIECE1>},   {"EST", makePlanner<og::EST>},
      {"KPIECE1", makePlanner<og::KPIECE1>},     {"LazyPRM", makePlanner<og::LazyPRM>},
      {"LBKPIECE1", makePlanner<og::LBKPIECE1>}, {"PRM", makePlanner<og::PRM>},
      {"PRMstar", makePlanner<og::PRMstar>},     {"RRT", makePlanner<og::RRT>},
      {"RRTConnect", makePlanner<og::RRTConnect>}, {"RRTstar", makePlanner<og::RRTstar>},
      {"SBL", makePlanner<og::SBL>},             {"TRRT", makePlanner<og::TRRT>},
  };
  return factories;
}

std::string canonicalPlannerId(const std::string& id) {
  static const std::string kMoveItSuffix = "kConfigDefault";
  if (id.size() > kMoveItSuffix.size() && id.compare(id.size() - kMoveItSuffix.size(), std::string::npos,
                                                     kMoveItSuffix) == 0) {
    return id.substr(0, id.size() - kMoveItSuffix.size());
  }
  return id;
}

std::string joinIds() {
  std::string out;
  for (const std::string& id : availablePlannerIds()) out += (out.empty() ? "" : ", ") + id;
  return out;
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

bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

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

// Everything one plan() call shares between its attempts.
struct Session {
  std::shared_ptr<const JointSpace> joint_space;
  ob::SpaceInformationPtr si;
  std::shared_ptr<const JointSpace> coarse_space;
  ob::SpaceInformationPtr coarse_si;  // same space, coarser motion checks: see simplifyPath()
  std::atomic<std::size_t> checks{0};
  JointValidityFn is_valid;
  JointValidityExplainFn explain;

  bool valid(const Eigen::VectorXd& q) {
    ++checks;
    return is_valid(q);
  }

  // Space information over `space` whose validity checker counts its checks here, with motions checked at
  // `fraction` of the space's maximum extent.
  ob::SpaceInformationPtr spaceInformation(const std::shared_ptr<const JointSpace>& space, double fraction) {
    auto si = std::make_shared<ob::SpaceInformation>(space->space());
    si->setStateValidityChecker(std::make_shared<CallbackValidityChecker>(
        si, space, [this](const Eigen::VectorXd& q) { return valid(q); }));
    si->setStateValidityCheckingResolution(fraction);
    si->setup();
    return si;
  }

  std::string reason(const Eigen::VectorXd& q) const {
    if (!explain) return "";
    const std::string why = explain(q);
    return why.empty() ? "" : ": " + why;
  }
};

struct GoalSet : Result<PlanningStatus> {
  std::vector<Eigen::VectorXd> states;
};

GoalSet fail(PlanningStatus status, std::string message) {
  GoalSet g;
  g.fail(status, std::move(message));
  return g;
}

void addDistinct(const std::vector<JointBounds>& joints, const Eigen::VectorXd& q, std::vector<Eigen::VectorXd>* out) {
  for (const Eigen::VectorXd& s : *out) {
    if (jointDistance(joints, s, q) < kDuplicateGoalDistance) return;
  }
  out->push_back(q);
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
    if (session->valid(q)) {
      addDistinct(p.joints, q, &set.states);
    } else if (produced == 1) {
      first_reason = session->reason(q);
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

struct Attempt {
  ob::PlannerStatus status = ob::PlannerStatus::UNKNOWN;
  std::vector<Eigen::VectorXd> raw_path;  // OMPL's values (continuous joints wrapped)
  double length = std::numeric_limits<double>::infinity();
  std::string error;  // planner configuration error
  double simplify_time = 0.0;
  bool simplify_fallback = false;
};

std::vector<Eigen::VectorXd> unwind(const std::vector<JointBounds>& joints, const Eigen::VectorXd& start,
                                    const std::vector<Eigen::VectorXd>& raw) {
  std::vector<Eigen::VectorXd> path{start};
  for (std::size_t k = 1; k < raw.size(); ++k) {
    Eigen::VectorXd q = raw[k];
    for (std::size_t i = 0; i < joints.size(); ++i) {
      if (joints[i].continuous) q[i] = path.back()[i] + shortestAngle(raw[k - 1][i], raw[k][i]);
    }
    path.push_back(q);
  }
  return path;
}

std::vector<Eigen::VectorXd> densify(const std::vector<Eigen::VectorXd>& path, double max_step) {
  if (max_step <= 0.0 || path.size() < 2) return path;
  std::vector<Eigen::VectorXd> out{path.front()};
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Eigen::VectorXd delta = path[k] - path[k - 1];
    const int steps = std::max(1, static_cast<int>(std::ceil(delta.cwiseAbs().maxCoeff() / max_step - 1e-12)));
    for (int s = 1; s < steps; ++s) out.push_back(path[k - 1] + delta * (static_cast<double>(s) / steps));
    out.push_back(path[k]);
  }
  return out;
}

// True if every segment of the path is valid at the session's (fine) resolution.
bool pathValid(const ob::SpaceInformationPtr& si, const og::PathGeometric& path) {
  for (std::size_t k = 1; k < path.getStateCount(); ++k) {
    if (!si->checkMotion(path.getState(k - 1), path.getState(k))) return false;
  }
  return true;
}

// OMPL's simplifier (vertex reduction, shortcutting, better goals, B-spline smoothing) spends most of its
// checks validating shortcuts that later shortcuts replace. It therefore runs first on a copy of the path
// whose motions are checked simplify_coarse_factor times coarser, and the result is then checked at the
// planning resolution; if any segment fails there, the simplifier runs again at the planning resolution.
// The returned path is thus always valid at the planning resolution.
og::PathGeometric simplifyPath(Session* session, const ob::GoalPtr& goal, const og::PathGeometric& raw,
                               double time_limit, bool* fell_back) {
  const ob::SpaceInformationPtr& fine = session->si;
  *fell_back = false;
  if (session->coarse_si) {
    og::PathGeometric coarse(session->coarse_si);
    for (std::size_t k = 0; k < raw.getStateCount(); ++k) coarse.append(raw.getState(k));
    og::PathSimplifier simplifier(session->coarse_si, goal);
    simplifier.simplify(coarse, ob::timedPlannerTerminationCondition(time_limit));
    og::PathGeometric out(fine);
    for (std::size_t k = 0; k < coarse.getStateCount(); ++k) out.append(coarse.getState(k));
    if (pathValid(fine, out)) return out;
    *fell_back = true;
  }
  og::PathGeometric out = raw;
  // The simplifier's loops are bounded; the time limit only guards against pathological validity checkers.
  og::PathSimplifier simplifier(fine, goal);
  simplifier.simplify(out, ob::timedPlannerTerminationCondition(time_limit));
  return out;
}

Attempt runAttempt(const PlanningProblem& p, Session* session, const PlannerFactory& factory,
                   const std::vector<Eigen::VectorXd>& goals, double time_limit) {
  Attempt attempt;
  const ob::SpaceInformationPtr& si = session->si;
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> start(si);
  session->joint_space->toOmpl(p.start, start.get());
  pdef->addStartState(start);
  auto goal = std::make_shared<ob::GoalStates>(si);
  for (const Eigen::VectorXd& q : goals) {
    ob::ScopedState<> s(si);
    session->joint_space->toOmpl(q, s.get());
    goal->addState(s);
  }
  pdef->setGoal(goal);

  ob::PlannerPtr planner = factory(si);
  for (const auto& [key, value] : p.options.planner_params) {
    if (!planner->params().hasParam(key) || !planner->params().setParam(key, value)) {
      attempt.error = "planner " + planner->getName() + " rejects parameter " + key + " = '" + value + "'";
      return attempt;
    }
  }
  planner->setProblemDefinition(pdef);
  planner->setup();
  attempt.status = planner->solve(ob::timedPlannerTerminationCondition(time_limit));
  if (attempt.status != ob::PlannerStatus::EXACT_SOLUTION) return attempt;

  og::PathGeometric path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  if (p.options.simplify) {
    const Clock::time_point t0 = Clock::now();
    path = simplifyPath(session, goal, path, p.options.allowed_planning_time, &attempt.simplify_fallback);
    attempt.simplify_time = secondsSince(t0);
  }
  for (std::size_t k = 0; k < path.getStateCount(); ++k) {
    attempt.raw_path.push_back(session->joint_space->fromOmpl(path.getState(k)));
  }
  attempt.length = 0.0;
  for (std::size_t k = 1; k < attempt.raw_path.size(); ++k) {
    attempt.length += jointDistance(p.joints, attempt.raw_path[k - 1], attempt.raw_path[k]);
  }
  return attempt;
}

PlanningResult finish(PlanningResult r, PlanningStatus status, std::string message, Clock::time_point t0,
                      const Session* session) {
  r.fail(status, std::move(message));
  r.planning_time = secondsSince(t0);
  if (session) r.validity_checks = session->checks.load();
  return r;
}

}  // namespace

const char* toString(PlanningStatus status) {
  static constexpr const char* kNames[] = {"SUCCESS",           "INVALID_REQUEST", "INVALID_START", "INVALID_GOAL",
                                           "GOAL_IN_COLLISION", "NO_IK_SOLUTION",  "TIMED_OUT",     "PLANNING_FAILED"};
  return enumName<PlanningStatus::kPlanningFailed>(status, kNames);
}

std::vector<std::string> availablePlannerIds() {
  std::vector<std::string> ids;
  for (const auto& entry : plannerFactories()) ids.push_back(entry.first);
  return ids;
}

double jointDistance(const std::vector<JointBounds>& joints, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const double d = jointDelta(joints[i], a[i], b[i]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

double maxJointDelta(const std::vector<JointBounds>& joints, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < joints.size(); ++i) m = std::max(m, std::abs(jointDelta(joints[i], a[i], b[i])));
  return m;
}

PlanningResult plan(const PlanningProblem& p) {
  const Clock::time_point t0 = Clock::now();
  PlanningResult result;
  const PlanningOptions& options = p.options;
  result.planner_id = canonicalPlannerId(options.planner_id);

  std::string err = validateJoints(p.joints);
  if (err.empty()) err = validateOptions(options);
  if (err.empty() && !p.is_valid) err = "no state validity function given";
  if (!err.empty()) return finish(result, PlanningStatus::kInvalidRequest, err, t0, nullptr);
  const auto factory = plannerFactories().find(result.planner_id);
  if (factory == plannerFactories().end()) {
    return finish(result, PlanningStatus::kInvalidRequest,
                  "unknown planner id '" + options.planner_id + "'; valid ids: " + joinIds(), t0, nullptr);
  }
  err = shapeError(p.joints.size(), p.start);
  if (!err.empty()) return finish(result, PlanningStatus::kInvalidRequest, "start state " + err, t0, nullptr);
  const int goal_kinds = (p.joint_goal ? 1 : 0) + (p.goal_states.empty() ? 0 : 1) + (p.sampled_goal ? 1 : 0);
  if (goal_kinds != 1) {
    return finish(result, PlanningStatus::kInvalidRequest,
                  "exactly one goal kind (joint_goal, goal_states, sampled_goal) must be given, got " +
                      std::to_string(goal_kinds),
                  t0, nullptr);
  }

  if (options.seed) {
    // OMPL logs an error when reseeding after its first use; reseeding is what we want here.
    const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(*options.seed);
    ompl::msg::setLogLevel(level);
  }

  Session session;
  session.is_valid = p.is_valid;
  session.explain = p.explain_invalid;
  session.joint_space = std::make_shared<JointSpace>(p.joints);
  session.joint_space->space()->registerDefaultProjection(
      std::make_shared<FirstJointsProjection>(session.joint_space.get()));
  const double extent = session.joint_space->space()->getMaximumExtent();
  const double fraction = options.longest_valid_segment_length > 0.0
                              ? std::min(1.0, options.longest_valid_segment_length / extent)
                              : options.longest_valid_segment_fraction;
  session.si = session.spaceInformation(session.joint_space, fraction);
  // The coarse pass never checks coarser than kCoarsestSimplifyFraction: where the planning resolution is
  // already that coarse (MoveIt's default), shortcuts accepted coarser fail their re-check too often to pay.
  const double coarse_fraction =
      std::min(fraction * options.simplify_coarse_factor, std::max(fraction, kCoarsestSimplifyFraction));
  if (options.simplify && coarse_fraction > fraction) {
    // A state space owns its check resolution, so the coarse checks need a space of their own.
    session.coarse_space = std::make_shared<JointSpace>(p.joints);
    session.coarse_si = session.spaceInformation(session.coarse_space, coarse_fraction);
  }

  err = boundsViolation(p.joints, p.start);
  if (!err.empty()) return finish(result, PlanningStatus::kInvalidStart, "start state: " + err, t0, &session);
  if (!session.valid(p.start)) {
    return finish(result, PlanningStatus::kInvalidStart,
                  "start state " + formatState(p.start) + " is invalid" + session.reason(p.start), t0, &session);
  }

  const GoalSet goals = p.joint_goal     ? jointGoalStates(p, &session)
                        : p.sampled_goal ? sampledGoalStates(p, &session)
                                         : explicitGoalStates(p, &session);
  if (!goals.ok()) return finish(result, goals.status, goals.message, t0, &session);

  const int attempts = options.num_planning_attempts;
  std::vector<Attempt> outcomes(attempts);
  if (options.parallel_attempts && attempts > 1) {
    const double time_limit = std::max(0.0, options.allowed_planning_time - secondsSince(t0));
    std::vector<std::thread> threads;
    for (int a = 0; a < attempts; ++a) {
      threads.emplace_back(
          [&, a] { outcomes[a] = runAttempt(p, &session, factory->second, goals.states, time_limit); });
    }
    for (std::thread& t : threads) t.join();
  } else {
    for (int a = 0; a < attempts; ++a) {
      const double remaining = std::max(0.0, options.allowed_planning_time - secondsSince(t0));
      outcomes[a] = runAttempt(p, &session, factory->second, goals.states, remaining / (attempts - a));
      if (!outcomes[a].error.empty()) break;
    }
  }

  const Attempt* best = nullptr;
  std::set<std::string> failures;
  bool timed_out = false;
  for (const Attempt& a : outcomes) {
    if (!a.error.empty()) return finish(result, PlanningStatus::kInvalidRequest, a.error, t0, &session);
    if (a.status == ob::PlannerStatus::EXACT_SOLUTION) {
      ++result.solved_attempts;
      if (!best || a.length < best->length) best = &a;
    } else if (a.status == ob::PlannerStatus::TIMEOUT || a.status == ob::PlannerStatus::APPROXIMATE_SOLUTION) {
      timed_out = true;
    } else {
      failures.insert(a.status.asString());
    }
  }
  if (!best) {
    std::ostringstream msg;
    msg << result.planner_id << " found no solution in " << options.allowed_planning_time << " s ("
        << attempts << " attempt" << (attempts > 1 ? "s" : "") << ")";
    for (const std::string& f : failures) msg << "; OMPL: " << f;
    return finish(result, timed_out ? PlanningStatus::kTimeout : PlanningStatus::kPlanningFailed, msg.str(), t0,
                  &session);
  }
  result.path = densify(unwind(p.joints, p.start, best->raw_path), options.max_joint_step);
  result.path_length = best->length;
  result.simplification_time = best->simplify_time;
  result.simplification_fallback = best->simplify_fallback;
  return finish(result, PlanningStatus::kSuccess, "", t0, &session);
}

}  // namespace sixdof_core
