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
#include <ompl/base/goals/GoalStates.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "planning/ompl_setup.h"
#include "planning/request.h"

// The query: attempts (threads), path simplification and post-processing, and plan() itself. The OMPL joint
// space and planner registry are in planning/ompl_setup.*, request validation and goal states in
// planning/request.*.

namespace sixdof_core {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using detail::boundsViolation;
using detail::canonicalPlannerId;
using detail::FirstJointsProjection;
using detail::formatState;
using detail::GoalSet;
using detail::jointDelta;
using detail::JointSpace;
using detail::PlannerFactory;
using detail::plannerFactories;
using detail::Session;
using detail::shapeError;
using detail::shortestAngle;
using detail::validateJoints;
using detail::validateOptions;

using Clock = std::chrono::steady_clock;

// The coarsest check resolution (fraction of the space's maximum extent) of the simplifier's coarse pass.
constexpr double kCoarsestSimplifyFraction = 0.005;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string joinIds() {
  std::string out;
  for (const std::string& id : availablePlannerIds()) out += (out.empty() ? "" : ", ") + id;
  return out;
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

// The simplification's bounds: rounds of vertex reduction, then of shortcutting, each stopping early at a round
// that changes nothing.
constexpr int kReduceRounds = 3;
constexpr int kShortcutRounds = 5;
// A shortcutting round makes this many tries, or one per vertex of the path at the round's start if more. The
// planner's path usually reduces to three vertices, so one try per vertex
// (OMPL's shortcutPath) would leave the result to three draws: summed path length over plan_bench's queries 233 rad
// that way, 184 rad with 12 tries and the gain below, in a fifth fewer instructions.
constexpr int kMinShortcutTries = 12;
// A shortcut is checked only if it would shorten the path by at least this share of its length. Motions along the
// obstacles the path already hugs cost the most to check and gain the least.
constexpr double kMinShortcutGain = 0.05;
// Random points closer than this share of the path's length to a vertex are taken at the vertex.
constexpr double kShortcutSnap = 0.005;

// A point along a path: vertex `vertex`, or (vertex < 0) the point `t` of the way along segment `segment`, at arc
// length `at`.
struct PathPoint {
  int segment = 0;
  int vertex = -1;
  double t = 0.0;
  double at = 0.0;
};

PathPoint pointAt(const std::vector<double>& arc, double at) {
  PathPoint p;
  const int after = static_cast<int>(std::upper_bound(arc.begin(), arc.end(), at) - arc.begin());
  p.segment = std::clamp(after - 1, 0, static_cast<int>(arc.size()) - 2);
  const double snap = kShortcutSnap * arc.back();
  if (at - arc[p.segment] < snap) {
    p.vertex = p.segment;
  } else if (arc[p.segment + 1] - at < snap) {
    p.vertex = p.segment + 1;
  }
  if (p.vertex >= 0) {
    p.at = arc[p.vertex];
  } else {
    p.t = (at - arc[p.segment]) / (arc[p.segment + 1] - arc[p.segment]);
    p.at = at;
  }
  return p;
}

// One round of shortcutting: two random points anywhere along the path, and the stretch between them replaced by
// the straight motion when that is valid and shortens the path by at least kMinShortcutGain of its length.
bool shortcutRound(const ob::SpaceInformationPtr& si, og::PathGeometric* path, ompl::RNG* rng) {
  std::vector<ob::State*>& states = path->getStates();
  if (states.size() < 3) return false;
  const int tries = std::max(kMinShortcutTries, static_cast<int>(states.size()));
  std::vector<double> arc;  // arc length from the start at each vertex
  const auto measure = [&] {
    arc.assign(states.size(), 0.0);
    for (std::size_t k = 1; k < states.size(); ++k) arc[k] = arc[k - 1] + si->distance(states[k - 1], states[k]);
  };
  measure();
  if (!(arc.back() > 0.0)) return false;
  ob::State* scratch[2] = {si->allocState(), si->allocState()};
  bool changed = false;
  for (int i = 0; i < tries; ++i) {
    double u = rng->uniformReal(0.0, arc.back()), v = rng->uniformReal(0.0, arc.back());
    if (u > v) std::swap(u, v);
    const PathPoint ends[2] = {pointAt(arc, u), pointAt(arc, v)};
    // The vertices strictly between the two points: first..last.
    const int first = ends[0].vertex >= 0 ? ends[0].vertex + 1 : ends[0].segment + 1;
    const int last = ends[1].vertex >= 0 ? ends[1].vertex - 1 : ends[1].segment;
    if (last < first) continue;
    const ob::State* s[2];
    for (int e = 0; e < 2; ++e) {
      const PathPoint& p = ends[e];
      if (p.vertex >= 0) {
        s[e] = states[p.vertex];
      } else {
        si->getStateSpace()->interpolate(states[p.segment], states[p.segment + 1], p.t, scratch[e]);
        s[e] = scratch[e];
      }
    }
    if ((ends[1].at - ends[0].at) - si->distance(s[0], s[1]) < kMinShortcutGain * arc.back()) continue;
    if (!si->checkMotion(s[0], s[1])) continue;
    std::vector<ob::State*> next(states.begin(), states.begin() + first);
    for (int e = 0; e < 2; ++e) {
      if (ends[e].vertex < 0) next.push_back(si->cloneState(scratch[e]));
    }
    for (int k = first; k <= last; ++k) si->freeState(states[k]);
    next.insert(next.end(), states.begin() + last + 1, states.end());
    states.swap(next);
    measure();
    changed = true;
  }
  si->freeState(scratch[0]);
  si->freeState(scratch[1]);
  return changed;
}

// A bounded sequence of simplification steps (in place of OMPL's simplify(), which repeats rounds while they
// improve and time remains, and adds better-goal search, B-spline smoothing and a repair pass): OMPL's vertex
// reduction, trying connections anywhere along the path (range ratio 1), close vertices collapsed, then our
// shortcutting.
void simplifySteps(const ob::SpaceInformationPtr& si, og::PathGeometric* path) {
  og::PathSimplifier simplifier(si);
  for (int r = 0; r < kReduceRounds && simplifier.reduceVertices(*path, 0, 0, 1.0); ++r) {
  }
  simplifier.collapseCloseVertices(*path);
  // Drawn from OMPL's seed generator after the simplifier's own: a seeded plan stays repeatable.
  ompl::RNG rng;
  for (int r = 0; r < kShortcutRounds && shortcutRound(si, path, &rng); ++r) {
  }
}

// The simplifier runs first on a copy of the path whose motions are checked simplify_coarse_factor times
// coarser, and the result is then checked at the planning resolution; if any segment fails there, it runs
// again at the planning resolution. The returned path is thus always valid at the planning resolution.
og::PathGeometric simplifyPath(Session* session, const std::vector<JointBounds>& joints, const og::PathGeometric& raw,
                               bool* fell_back) {
  const ob::SpaceInformationPtr& fine = session->si;
  *fell_back = false;
  if (session->coarse_fraction > 0.0) {
    const ob::SpaceInformationPtr& coarse_si = session->coarseSpaceInformation(joints);
    og::PathGeometric coarse(coarse_si);
    for (std::size_t k = 0; k < raw.getStateCount(); ++k) coarse.append(raw.getState(k));
    simplifySteps(coarse_si, &coarse);
    og::PathGeometric out(fine);
    for (std::size_t k = 0; k < coarse.getStateCount(); ++k) out.append(coarse.getState(k));
    if (pathValid(fine, out)) return out;
    *fell_back = true;
  }
  og::PathGeometric out = raw;
  simplifySteps(fine, &out);
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
    path = simplifyPath(session, p.joints, path, &attempt.simplify_fallback);
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
  r.status = status;  // kSuccess too: finish() ends every path of plan()
  r.message = std::move(message);
  r.planning_time = secondsSince(t0);
  if (session) {
    r.validity_checks = session->checks.load();
    r.precheck_calls = session->precheck_calls.load();
    r.precheck_states = session->precheck_states.load();
  }
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
  if (options.precheck) session.precheck = p.precheck;
  session.joint_space = std::make_shared<JointSpace>(p.joints);
  const double extent = session.joint_space->space()->getMaximumExtent();
  const double fraction = options.longest_valid_segment_length > 0.0
                              ? std::min(1.0, options.longest_valid_segment_length / extent)
                              : options.longest_valid_segment_fraction;
  session.si = session.spaceInformation(session.joint_space, fraction);
  // The coarse pass never checks coarser than kCoarsestSimplifyFraction: where the planning resolution is
  // already that coarse (MoveIt's default), shortcuts accepted coarser fail their re-check too often to pay.
  const double coarse_fraction =
      std::min(fraction * options.simplify_coarse_factor, std::max(fraction, kCoarsestSimplifyFraction));
  if (options.simplify && coarse_fraction > fraction) session.coarse_fraction = coarse_fraction;

  err = boundsViolation(p.joints, p.start);
  if (!err.empty()) return finish(result, PlanningStatus::kInvalidStart, "start state: " + err, t0, &session);
  if (!session.valid(p.start)) {
    return finish(result, PlanningStatus::kInvalidStart,
                  "start state " + formatState(p.start) + " is invalid" + session.reason(p.start), t0, &session);
  }

  const GoalSet goals = p.joint_goal     ? detail::jointGoalStates(p, &session)
                        : p.sampled_goal ? detail::sampledGoalStates(p, &session)
                                         : detail::explicitGoalStates(p, &session);
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
