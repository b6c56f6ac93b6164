#include "sixdof_core/planning_context.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>

#include "sixdof_core/ik_analytic.h"

namespace sixdof_core {
namespace {

// Two IK solutions closer than this in every joint are the same solution.
constexpr double kSameSolution = 1e-9;

// The seed of an unseeded request's goal sampler: the next number of a process-wide generator seeded once from
// std::random_device. A std::random_device draw took 16 us on the 2-core virtual machines the benchmarks run on
// (RDSEED is slow under their hypervisor): a twentieth of a fast plan, outside its planning time.
std::uint64_t freshSeed() {
  static std::mutex mutex;
  static std::mt19937_64 generator{std::random_device()()};
  const std::lock_guard<std::mutex> lock(mutex);
  return generator();
}

}  // namespace

PlanningContext::PlanningContext(RobotModelConstPtr model, std::shared_ptr<const CollisionScene> scene,
                                 const std::string& group, std::shared_ptr<const IkSolver> ik)
    : model_(std::move(model)), scene_(std::move(scene)), ik_(std::move(ik)), group_(group) {
  if (!model_ || !scene_) throw std::invalid_argument("PlanningContext needs a robot model and a collision scene");
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown planning group '" + group + "'");
  for (const std::string& name : g->active_joints) {
    const JointModel& joint = model_->joint(name);
    JointBounds bounds{name, joint.limits.lower, joint.limits.upper, !joint.limits.bounded};
    if (bounds.continuous) bounds.lower = bounds.upper = 0.0;
    joints_.push_back(bounds);
    prismatic_.push_back(joint.type == JointType::kPrismatic);
    variable_indices_.push_back(joint.variable_index);
  }
  if (joints_.empty()) throw std::invalid_argument("planning group '" + group + "' has no active joints");
  if (ik_ && ik_->chain().jointNames() != g->active_joints) {
    throw std::invalid_argument("IK solver chain " + ik_->chain().baseLink() + " -> " + ik_->chain().tipLink() +
                                " does not have the joints of group '" + group + "'");
  }
  for (const std::string& link : scene_->linkNames()) {
    const int index = model_->linkIndex(link);
    if (index < 0) throw std::invalid_argument("collision scene link '" + link + "' is not in the robot model");
    scene_link_to_model_.push_back(index);
  }
  computeMotionGains();
}

void PlanningContext::computeMotionGains() {
  const std::size_t links = scene_link_to_model_.size();
  motion_gains_.assign(links, {});
  // The group variable a joint moves with, and by what factor (a mimic joint follows its source); -1: it stays.
  const auto& model_joints = model_->joints();
  std::vector<int> moved_by(model_joints.size(), -1);
  std::vector<double> factor(model_joints.size(), 1.0);
  for (std::size_t j = 0; j < model_joints.size(); ++j) {
    const JointModel& joint = model_joints[j];
    const int source = joint.mimic ? joint.mimic->joint_index : static_cast<int>(j);
    const auto v = std::find(variable_indices_.begin(), variable_indices_.end(), model_joints[source].variable_index);
    if (model_joints[source].variable_index < 0 || v == variable_indices_.end()) continue;
    moved_by[j] = static_cast<int>(v - variable_indices_.begin());
    if (joint.mimic) factor[j] = std::abs(joint.mimic->multiplier);
  }
  // Up the tree from each link: a revolute joint's axis passes through its child link's origin, so it moves a point
  // p of the link at most |p| plus the distance from there to the link's origin, bounded by the joint offsets
  // (and the travel of prismatic joints) between them.
  for (std::size_t i = 0; i < links; ++i) {
    double lever = 0.0;
    for (int link = scene_link_to_model_[i]; model_->links()[link].parent_joint >= 0;
         link = model_->links()[link].parent_link) {
      const int j = model_->links()[link].parent_joint;
      const JointModel& joint = model_joints[j];
      const bool prismatic = joint.type == JointType::kPrismatic;
      if (moved_by[j] >= 0 && joint.type != JointType::kFixed) {
        motion_gains_[i].push_back(MotionGain{j, link, moved_by[j], factor[j], prismatic, lever});
      }
      lever += joint.origin.translation().norm();
      if (prismatic) lever += std::max(std::abs(joint.limits.lower), std::abs(joint.limits.upper));
    }
  }
}

void PlanningContext::setPathConstraints(const PathConstraints& constraints) {
  std::vector<JointBounds> joints = joints_;
  for (const JointBounds& c : constraints.joint_bounds) {
    auto it = std::find_if(joints.begin(), joints.end(), [&](const JointBounds& j) { return j.name == c.name; });
    if (it == joints.end()) {
      throw std::invalid_argument("path constraint on joint '" + c.name + "', which is not an active joint of group '" +
                                  group_ + "'");
    }
    if (!(std::isfinite(c.lower) && std::isfinite(c.upper) && c.lower <= c.upper)) {
      throw std::invalid_argument("path constraint on joint '" + c.name + "' has an empty or non-finite range");
    }
    if (it->continuous) {
      if (c.upper - c.lower < 2.0 * M_PI) *it = JointBounds{it->name, c.lower, c.upper, false};
      continue;
    }
    const double lower = std::max(it->lower, c.lower);
    const double upper = std::min(it->upper, c.upper);
    if (lower > upper) {
      throw std::invalid_argument("path constraint on joint '" + c.name + "' allows no value within its limits [" +
                                  std::to_string(it->lower) + ", " + std::to_string(it->upper) + "]");
    }
    it->lower = lower;
    it->upper = upper;
  }
  joints_ = joints;
  constrained_joints_ = !constraints.joint_bounds.empty();
  state_constraint_ = constraints.state;
  explain_constraint_ = constraints.explain;
}

std::string PlanningContext::pathConstraintViolation(const RobotState& reference, const Eigen::VectorXd& values) const {
  if (constrained_joints_) {
    for (std::size_t i = 0; i < joints_.size(); ++i) {
      const JointBounds& j = joints_[i];
      if (!j.continuous && (values[i] < j.lower || values[i] > j.upper)) {
        return "joint " + j.name + " = " + std::to_string(values[i]) + " is outside its path constraint [" +
               std::to_string(j.lower) + ", " + std::to_string(j.upper) + "]";
      }
    }
  }
  if (state_constraint_) {
    const RobotState state = withGroup(reference, values);
    if (!state_constraint_(state)) {
      return explain_constraint_ ? explain_constraint_(state) : "the state violates the path constraints";
    }
  }
  return "";
}

RobotState PlanningContext::withGroup(const RobotState& reference, const Eigen::VectorXd& values) const {
  RobotState state = reference;
  state.setVariablePositions(variable_indices_, values);
  return state;
}

std::vector<Eigen::Isometry3d> PlanningContext::sceneLinkPoses(const RobotState& state) const {
  std::vector<Eigen::Isometry3d> poses;
  sceneLinkPoses(state, &poses);
  return poses;
}

void PlanningContext::sceneLinkPoses(const RobotState& state, std::vector<Eigen::Isometry3d>* out) const {
  out->resize(scene_link_to_model_.size());
  for (std::size_t i = 0; i < scene_link_to_model_.size(); ++i) (*out)[i] = state.linkTransform(scene_link_to_model_[i]);
}

namespace {

// A fresh id for the scratch state of the callbacks made from one reference state (scratchState()).
std::uint64_t newScratchId() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

// The calling thread's scratch state for the callbacks with id `scratch`, made from `reference`, with the group's
// variables (`indices`) at `q`. The callbacks run concurrently in parallel planning attempts, hence one per thread; it
// is reset to the reference when another callback used it last, and otherwise keeps all but the group's values. Those
// set to the values they already hold leave the state (and its forward kinematics) as it is: the validity check of a
// state the pre-check has just failed to prove finds its link poses computed.
RobotState& scratchState(std::uint64_t scratch, const RobotState& reference, const std::vector<int>& indices,
                         const Eigen::VectorXd& q) {
  thread_local std::optional<RobotState> state;
  thread_local std::uint64_t state_scratch = 0;
  thread_local Eigen::VectorXd values;  // the group's values set last
  if (state && state_scratch == scratch && values.size() == q.size() && values == q) return *state;
  if (!state) {
    state.emplace(reference);
  } else if (state_scratch != scratch) {
    *state = reference;
  }
  state_scratch = scratch;
  state->setVariablePositions(indices, q);
  values = q;
  return *state;
}

}  // namespace

struct PlanningContext::Bound {
  PlanningContext self;
  RobotState reference;
};

std::shared_ptr<const PlanningContext::Bound> PlanningContext::bind(const RobotState& reference) const {
  return std::make_shared<const Bound>(Bound{*this, reference});
}

JointValidityFn PlanningContext::validityFn(const RobotState& reference) const {
  return makeValidityFn(bind(reference), newScratchId());
}

JointValidityFn PlanningContext::makeValidityFn(std::shared_ptr<const Bound> bound, std::uint64_t scratch) {
  return [bound = std::move(bound), scratch](const Eigen::VectorXd& q) {
    thread_local std::vector<Eigen::Isometry3d> poses;
    const PlanningContext& self = bound->self;
    if (self.constrained_joints_) {
      for (std::size_t i = 0; i < self.joints_.size(); ++i) {
        const JointBounds& j = self.joints_[i];
        if (!j.continuous && (q[i] < j.lower || q[i] > j.upper)) return false;
      }
    }
    const RobotState& state = scratchState(scratch, bound->reference, self.variable_indices_, q);
    if (self.state_constraint_ && !self.state_constraint_(state)) return false;
    self.sceneLinkPoses(state, &poses);
    return !self.scene_->isColliding(poses);
  };
}

JointValidityExplainFn PlanningContext::explainFn(const RobotState& reference) const {
  return makeExplainFn(bind(reference));
}

JointValidityExplainFn PlanningContext::makeExplainFn(std::shared_ptr<const Bound> bound) {
  return [bound = std::move(bound)](const Eigen::VectorXd& q) -> std::string {
    const PlanningContext& self = bound->self;
    std::string why = self.pathConstraintViolation(bound->reference, q);
    if (!why.empty()) return why;
    const CollisionReport report =
        self.scene_->checkCollision(self.sceneLinkPoses(self.withGroup(bound->reference, q)));
    std::set<std::pair<std::string, std::string>> pairs;
    for (const Contact& c : report.contacts) {
      if (pairs.insert({c.body1, c.body2}).second) {
        why += (why.empty() ? "" : ", ") + c.body1 + " collides with " + c.body2;
      }
    }
    return why;
  };
}

MotionPrecheckFn PlanningContext::precheckFn(const RobotState& reference) const {
  return makePrecheckFn(bind(reference), newScratchId());
}

MotionPrecheckFn PlanningContext::makePrecheckFn(std::shared_ptr<const Bound> bound, std::uint64_t scratch) {
  return [bound = std::move(bound), scratch](const Eigen::VectorXd& q, const Eigen::VectorXd& step, double cap,
                                             double tolerance) -> MotionPrecheck {
    thread_local std::vector<Eigen::Isometry3d> poses;
    thread_local LinkMotionBound motion;
    const PlanningContext& self = bound->self;
    const RobotState& state = scratchState(scratch, bound->reference, self.variable_indices_, q);
    self.sceneLinkPoses(state, &poses);
    // A revolute joint moves the link's origin at its step times the origin's distance from the joint's axis: now
    // at most the distance to the joint's child frame, growing by at most what the joints in between move it.
    motion.links.resize(poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      motion.links[i].clear();
      double inner_speed = 0.0;  // how fast the joints below the current one may move the link's origin, at most
      for (const MotionGain& gain : self.motion_gains_[i]) {
        const double amount = gain.factor * std::abs(step[gain.variable]);
        if (amount == 0.0) continue;
        if (gain.prismatic) {
          motion.links[i].push_back({gain.joint, amount, 0.0, 0.0});
          inner_speed += amount;
        } else {
          const double lever = (poses[i].translation() - state.linkTransform(gain.child_link).translation()).norm();
          motion.links[i].push_back({gain.joint, amount * lever, amount, amount * inner_speed});
          inner_speed += amount * gain.lever;
        }
      }
    }
    const SphereCertificate certificate = self.scene_->precheckMotion(poses, motion, cap, tolerance);
    return MotionPrecheck{certificate.proven, certificate.unprovable};
  };
}

PlanningProblem PlanningContext::problem(const RobotState& start, const PlanningOptions& options) const {
  PlanningProblem p;
  p.joints = joints_;
  const std::shared_ptr<const Bound> bound = bind(start);
  const std::uint64_t scratch = newScratchId();  // one scratch state for both: they alternate
  p.is_valid = makeValidityFn(bound, scratch);
  p.explain_invalid = makeExplainFn(bound);
  // The pre-check proves collision-freedom only: not a state constraint (joint bounds hold between bounded ends).
  if (!state_constraint_) p.precheck = makePrecheckFn(bound, scratch);
  p.start = start.groupPositions(group_);
  p.options = options;
  return p;
}

PlanningResult PlanningContext::planToJoints(const RobotState& start, const Eigen::VectorXd& goal, double tolerance,
                                             const PlanningOptions& options) const {
  PlanningProblem p = problem(start, options);
  p.joint_goal = JointGoal{goal, Eigen::VectorXd::Constant(goal.size(), tolerance)};
  return plan(p);
}

PlanningResult PlanningContext::planToNamed(const RobotState& start, const std::string& name, double tolerance,
                                            const PlanningOptions& options) const {
  const GroupState* named = model_->findGroupState(group_, name);
  if (!named) {
    PlanningResult result;
    result.fail(PlanningStatus::kInvalidRequest, "group '" + group_ + "' has no named state '" + name + "'; known:");
    for (const GroupState& s : model_->groupStates()) {
      if (s.group == group_) result.message += " '" + s.name + "'";
    }
    return result;
  }
  RobotState goal_state = start;
  goal_state.setToNamedState(group_, name);
  return planToJoints(start, goal_state.groupPositions(group_), tolerance, options);
}

SampledGoal PlanningContext::poseSampler(const RobotState& start, const Eigen::Isometry3d& tip_pose,
                                         const PoseGoalOptions& pose_goal, const PlanningOptions& options) const {
  struct SamplerState {
    std::mt19937_64 rng;
    int calls = 0;
    // A closed-form solver's other solutions, nearest the start first, handed out one per later call.
    std::vector<Eigen::VectorXd> others;
    std::size_t next = 0;
  };
  auto state = std::make_shared<SamplerState>();
  state->rng.seed(options.seed ? *options.seed : freshSeed());
  SampledGoal goal;
  goal.max_states = pose_goal.max_states;
  goal.max_calls = pose_goal.max_calls;
  // Path constraints may narrow the joints below their limits, which the solver keeps to.
  const auto within = [joints = joints_](const Eigen::VectorXd& q) {
    for (std::size_t i = 0; i < joints.size(); ++i) {
      if (!joints[i].continuous && (q[i] < joints[i].lower || q[i] > joints[i].upper)) return false;
    }
    return true;
  };
  // The closed-form solver gives every solution of a pose in one call, so after the first its others are handed
  // out in turn (random seeds would find the same few branches again and again). A position-only goal samples
  // orientations: random seeds, as with the other solvers.
  const auto* analytic = pose_goal.ik.position_only ? nullptr : dynamic_cast<const AnalyticIkSolver*>(ik_.get());
  goal.sampler = [ik = ik_, analytic, within, joints = joints_, seed0 = start.groupPositions(group_), tip_pose,
                  ik_options = pose_goal.ik, state](Eigen::VectorXd* out) {
    const bool first = state->calls++ == 0;
    if (analytic && !first) {
      if (state->next == state->others.size()) return false;
      *out = state->others[state->next++];
      return true;
    }
    IkOptions o = ik_options;
    // The first solution is the one nearest the start; later ones start from random seeds to find other branches.
    o.seed = seed0;
    if (!first) {
      for (std::size_t i = 0; i < joints.size(); ++i) {
        const double lo = joints[i].continuous ? -M_PI : joints[i].lower;
        const double hi = joints[i].continuous ? M_PI : joints[i].upper;
        o.seed[i] = std::uniform_real_distribution<double>(lo, hi)(state->rng);
      }
    }
    o.random_seed = state->rng();
    const IkResult r = ik->solve(tip_pose, o);
    if (!r.ok()) return false;
    if (analytic) {
      std::vector<std::pair<double, Eigen::VectorXd>> others;
      for (const Eigen::VectorXd& q : analytic->solveAll(tip_pose, seed0).solutions) {
        if ((q - r.solution).cwiseAbs().maxCoeff() > kSameSolution && within(q)) {
          others.emplace_back((q - seed0).squaredNorm(), q);
        }
      }
      std::stable_sort(others.begin(), others.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      for (auto& [distance, q] : others) state->others.push_back(std::move(q));
    }
    if (!within(r.solution)) return false;
    *out = r.solution;
    return true;
  };
  return goal;
}

PlanningResult PlanningContext::planToPose(const RobotState& start, const Eigen::Isometry3d& tip_pose,
                                           const PoseGoalOptions& pose_goal, const PlanningOptions& options) const {
  if (!ik_) {
    PlanningResult result;
    result.fail(PlanningStatus::kInvalidRequest, "group '" + group_ + "' has no IK solver: pose goals are unavailable");
    return result;
  }
  PlanningProblem p = problem(start, options);
  p.sampled_goal = poseSampler(start, tip_pose, pose_goal, options);
  return plan(p);
}

PlanningResult PlanningContext::planToPosition(const RobotState& start, const Eigen::Vector3d& tip_position,
                                               const PoseGoalOptions& pose_goal,
                                               const PlanningOptions& options) const {
  PoseGoalOptions position_goal = pose_goal;
  position_goal.ik.position_only = true;
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  target.translation() = tip_position;
  return planToPose(start, target, position_goal, options);
}

CartesianPathResult PlanningContext::cartesianPath(const RobotState& start,
                                                   const std::vector<Eigen::Isometry3d>& waypoints, double eef_step,
                                                   const JumpThreshold& jump_threshold, bool avoid_collisions,
                                                   const IkOptions& ik_options) const {
  if (!ik_) {
    CartesianPathResult result;
    result.fail(CartesianStatus::kInvalidRequest,
                "group '" + group_ + "' has no IK solver: Cartesian paths are unavailable");
    return result;
  }
  CartesianPathRequest request;
  request.start = start.groupPositions(group_);
  request.waypoints = waypoints;
  request.eef_step = eef_step;
  request.jump_threshold = jump_threshold;
  request.avoid_collisions = avoid_collisions;
  request.prismatic = prismatic_;
  request.fk = [ik = ik_](const Eigen::VectorXd& q) { return ik->chain().forward(q); };
  // Only the seed: random restarts would land on other branches, which is what jump detection is there to stop.
  request.ik = [ik = ik_, ik_options](const Eigen::Isometry3d& target, const Eigen::VectorXd& seed,
                                      Eigen::VectorXd* out) {
    IkOptions o = ik_options;
    o.seed = seed;
    o.attempts = 1;
    const IkResult r = ik->solve(target, o);
    if (!r.ok()) return false;
    *out = r.solution;
    return true;
  };
  request.is_valid = validityFn(start);
  request.explain_invalid = explainFn(start);
  return computeCartesianPath(request);
}

}  // namespace sixdof_core
