#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sixdof_core/result.h"

namespace sixdof_core {

// Joint-space motion planning with OMPL, decoupled from the robot model and the collision scene: the
// problem is plain data plus callbacks, so any model/scene (or a synthetic test world) plugs in.
//
// Joint values are in the order of PlanningProblem::joints. A continuous joint (no limits, e.g. a URDF
// "continuous" joint) is planned on the circle (OMPL SO2): paths take the short way round and are returned
// unwound, i.e. continuous from the start value (they may leave [-pi, pi)). A multi-turn joint with limits
// wider than 2 pi (e.g. [-2 pi, 2 pi]) is a bounded joint, not a continuous one.

// True if the joint state is valid (collision-free, ...). Called from the planning threads concurrently
// when attempts run in parallel, so it must be thread-safe (a const query on an immutable scene is).
using JointValidityFn = std::function<bool(const Eigen::VectorXd&)>;
// Optional: why a state is invalid (e.g. "link3 collides with table"), used only to word error messages.
using JointValidityExplainFn = std::function<std::string(const Eigen::VectorXd&)>;
// What a motion pre-check proves about the states q + w * step (continuous joints wrap): every one with |w| <= proven
// is valid, i.e. is_valid would accept it; proven = 0: not even q is (is_valid decides). Then none with
// |w| <= unprovable can be proven either.
struct MotionPrecheck {
  double proven = 0.0;
  double unprovable = 0.0;
};
// Optional pre-check of motions from q along a joint-space step, proving no more than `cap` (a fraction of the step).
// It must never overstate `proven`, and may understate it by up to `tolerance` (a cheaper proof). Thread-safe like
// is_valid.
using MotionPrecheckFn = std::function<MotionPrecheck(const Eigen::VectorXd& q, const Eigen::VectorXd& step,
                                                      double cap, double tolerance)>;
// Produces one goal state (e.g. one IK solution of a pose goal, randomly seeded); false = no solution.
// Calls are serialised by the planner, so the sampler need not be thread-safe.
using GoalSamplerFn = std::function<bool(Eigen::VectorXd* out)>;

struct JointBounds {
  std::string name;
  double lower = 0.0;  // not used for a continuous joint
  double upper = 0.0;
  bool continuous = false;
};

// Joint-space goal: satisfied by any state within +-tolerance (per joint) of the target. The target itself
// is used when valid; otherwise valid states are sampled inside the tolerance box (MoveIt's goal sampler).
struct JointGoal {
  Eigen::VectorXd target;
  Eigen::VectorXd tolerance;  // per joint, >= 0; empty = exact (0)
};

// Sampled goal (pose / position goals: the caller's IK wraps into GoalSamplerFn). The sampler is called until
// max_states valid distinct states were collected or max_calls calls were made; planning then connects to
// any of them (OMPL GoalStates).
struct SampledGoal {
  GoalSamplerFn sampler;
  int max_states = 8;
  int max_calls = 64;
};

enum class PlanningStatus {
  kSuccess,
  kInvalidRequest,   // malformed problem: sizes, NaN, bounds, unknown planner id, bad options
  kInvalidStart,     // start state out of bounds or invalid (message says which check failed)
  kInvalidGoal,      // goal state out of bounds
  kGoalInCollision,  // every goal state is invalid according to the validity function
  kNoIkSolution,     // the goal sampler never produced a state
  kTimeout,          // no (exact) solution within the allowed planning time
  kPlanningFailed,   // OMPL reported another failure
};

const char* toString(PlanningStatus status);

struct PlanningOptions {
  // OMPL geometric planner: see availablePlannerIds(). MoveIt's "<id>kConfigDefault" names are accepted.
  std::string planner_id = "RRTConnect";
  // Planner parameters by OMPL name (e.g. {"range", "0.5"}); an unknown name is an invalid request.
  std::map<std::string, std::string> planner_params;
  double allowed_planning_time = 5.0;  // s, for all attempts together
  int num_planning_attempts = 1;
  // Parallel attempts run in threads and the shortest solution wins; sequential attempts split the time.
  bool parallel_attempts = true;
  // Motions are checked at this fraction of the joint space's maximum extent (MoveIt's
  // longest_valid_segment_fraction) ...
  double longest_valid_segment_fraction = 0.005;
  // ... or, when > 0, at this joint-space distance (rad / m) instead.
  double longest_valid_segment_length = 0.0;
  bool simplify = true;  // bounded rounds of OMPL PathSimplifier's vertex reduction, then of shortcutting
  // > 1: the simplifier first checks its shortcuts this many times coarser than the planning resolution (but
  // never coarser than 0.005 of the space's maximum extent, MoveIt's default resolution), then re-checks the
  // simplified path at the planning resolution and, if any segment fails there, simplifies again at the
  // planning resolution. The path is valid at the planning resolution either way. 1 (the default) = off: with
  // the motion pre-check, the coarse pass and its re-check cost more than they save (plan_bench measures both).
  double simplify_coarse_factor = 1.0;
  // After simplification, points are inserted so no joint moves more than this between points (0 = off).
  double max_joint_step = 0.0;
  // Motions are checked at the same states either way; with the problem's pre-check, runs of them that it proves
  // valid skip is_valid. false: every state is checked with is_valid (the pre-check's baseline).
  bool precheck = true;
  // Reseeds OMPL's process-wide random generator: planning is then repeatable for sequential attempts
  // (or one attempt) with planners that stop at their first solution. Do not plan concurrently with it.
  std::optional<std::uint32_t> seed;
};

struct PlanningProblem {
  std::vector<JointBounds> joints;
  JointValidityFn is_valid;               // required
  JointValidityExplainFn explain_invalid;  // optional
  MotionPrecheckFn precheck;               // optional
  Eigen::VectorXd start;
  // Exactly one of the three goal kinds must be given.
  std::optional<JointGoal> joint_goal;
  std::vector<Eigen::VectorXd> goal_states;  // any of them
  std::optional<SampledGoal> sampled_goal;
  PlanningOptions options;
};

struct PlanningResult : Result<PlanningStatus> {
  std::vector<Eigen::VectorXd> path;  // start first, goal last; empty unless kSuccess
  double planning_time = 0.0;         // s, wall clock of the whole call
  double path_length = 0.0;           // sum of jointDistance() over the path's segments
  double simplification_time = 0.0;   // s, part of planning_time spent simplifying the returned path
  bool simplification_fallback = false;  // the coarse simplification failed its re-check (see options)
  std::size_t validity_checks = 0;    // calls of is_valid made by this call
  std::size_t precheck_calls = 0;     // calls of the pre-check made by this call
  std::size_t precheck_states = 0;    // motion states the pre-check proved valid (no is_valid call for them)
  int solved_attempts = 0;
  std::string planner_id;             // canonical id used
};

// Plans a collision-free joint path; never throws on bad input (returns kInvalidRequest with a message).
PlanningResult plan(const PlanningProblem& problem);

// Planner ids plan() accepts.
std::vector<std::string> availablePlannerIds();

// Euclidean joint-space distance; continuous joints contribute their shortest angle.
double jointDistance(const std::vector<JointBounds>& joints, const Eigen::VectorXd& a, const Eigen::VectorXd& b);
// Largest single-joint change from a to b.
double maxJointDelta(const std::vector<JointBounds>& joints, const Eigen::VectorXd& a, const Eigen::VectorXd& b);

}  // namespace sixdof_core
