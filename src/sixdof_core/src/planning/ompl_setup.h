#pragma once
// Private to planning: the joint space in OMPL terms (state space, projection, validity checker), the planner
// registry and the Session one plan() call shares between its attempts.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/Planner.h>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include "sixdof_core/planning.h"

namespace sixdof_core {
namespace detail {

namespace ob = ompl::base;

constexpr double kTwoPi = 2.0 * M_PI;
// KPIECE-style planners grid the projection (the first two joints, as MoveIt's default) in this many cells.
constexpr double kProjectionCellsPerJoint = 20.0;

// Signed shortest rotation from one angle to another, in [-pi, pi].
double shortestAngle(double from, double to);
// to - from, or the shortest angle for a continuous joint.
double jointDelta(const JointBounds& joint, double from, double to);

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
    // Set here so the state space's own default projection does not replace this one in setup(), and the bounds so
    // that setup() does not estimate them by sampling states (which would draw a seed from OMPL's generator).
    setCellSizes(cells);
    ob::RealVectorBounds bounds(getDimension());
    for (unsigned int i = 0; i < getDimension(); ++i) {
      const JointBounds& joint = joint_space_->joints()[i];
      bounds.setLow(i, joint.continuous ? -M_PI : joint.lower);
      bounds.setHigh(i, joint.continuous ? M_PI : joint.upper);
    }
    setBounds(bounds);
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


struct Session;

// See Session::precheckPays().
constexpr std::size_t kPrecheckTrial = 64;
constexpr std::size_t kPrecheckMinShare = 8;
// Runs of this many states or fewer go to is_valid without asking the pre-check: a call costs about as much as two
// states' checks.
constexpr int kShortRun = 2;
// Where the pre-check proves nothing about a state, is_valid also takes this many on each side of it (they are
// likely as close to an obstacle).
constexpr int kUnprovenNeighbours = 2;

// Checks a motion at the states OMPL's DiscreteMotionValidator checks (the state space's valid segment count: s2
// and the evenly spaced states between), with the same answer, but lets the session's pre-check prove runs of them
// valid at once: a state it proves free takes the states within its proven stretch of the motion with it; a state
// it proves nothing about goes to the validity checker. In the order of OMPL's: bisection (the middle of each open
// run first), or, for the last valid state, from s1 on.
class PrecheckMotionValidator : public ob::MotionValidator {
 public:
  PrecheckMotionValidator(const ob::SpaceInformationPtr& si, std::shared_ptr<const JointSpace> joint_space,
                          Session* session)
      : ob::MotionValidator(si), joint_space_(std::move(joint_space)), session_(session) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override;
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override;

 private:
  // The motion's states k = 1..n (s1 + k/n of the way to s2; n = the valid segment count).
  struct Motion {
    const ob::State* s1;
    const ob::State* s2;
    int n;
    Eigen::VectorXd from;
    Eigen::VectorXd step;  // to s2, continuous joints the short way round
  };
  Motion motion(const ob::State* s1, const ob::State* s2) const;
  // What the pre-check proves around state k, in states on each side (looking up to `reach` states away): proven
  // (-1: not even state k), or, then, how many it cannot prove (is_valid decides them).
  struct Around {
    int proven = -1;
    int unprovable = 0;
  };
  Around precheck(const Motion& m, int k, int reach) const;
  // State k by is_valid; `test` is scratch.
  bool stateValid(const Motion& m, int k, ob::State* test) const;
  // The first invalid one of the states 1..n, or n + 1.
  int firstInvalid(const Motion& m) const;

  std::shared_ptr<const JointSpace> joint_space_;
  Session* session_;
};

using PlannerFactory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

// Every OMPL geometric planner plan() offers, by id.
const std::map<std::string, PlannerFactory>& plannerFactories();
// The id without MoveIt's "kConfigDefault" suffix.
std::string canonicalPlannerId(const std::string& id);

// Everything one plan() call shares between its attempts.
struct Session {
  std::shared_ptr<const JointSpace> joint_space;
  ob::SpaceInformationPtr si;
  double coarse_fraction = 0.0;  // > 0: the simplification checks motions this coarse first (see simplifyPath())
  std::atomic<std::size_t> checks{0};
  std::atomic<std::size_t> precheck_calls{0};
  std::atomic<std::size_t> precheck_states{0};
  std::atomic<std::size_t> precheck_proofs{0};  // calls that proved something
  JointValidityFn is_valid;
  JointValidityExplainFn explain;
  MotionPrecheckFn precheck;  // empty: motions are checked with OMPL's DiscreteMotionValidator

  bool valid(const Eigen::VectorXd& q) {
    ++checks;
    return is_valid(q);
  }

  MotionPrecheck prove(const Eigen::VectorXd& q, const Eigen::VectorXd& step, double cap, double tolerance) {
    ++precheck_calls;
    const MotionPrecheck p = precheck(q, step, cap, tolerance);
    if (p.proven > 0.0) ++precheck_proofs;
    return p;
  }

  // Whether asking the pre-check still pays in this query: after its first kPrecheckTrial calls, only while at least
  // one in kPrecheckMinShare proves something. A scene where it cannot (e.g. self pairs always closer than the
  // spheres' overshoot, from an SRDF without its "Never" pairs) then costs little more than without it.
  bool precheckPays() const {
    const std::size_t calls = precheck_calls.load();
    return calls < kPrecheckTrial || precheck_proofs.load() * kPrecheckMinShare >= calls;
  }

  // Space information over `space` (given FirstJointsProjection as its default projection) whose validity checker
  // counts its checks here, with motions checked at `fraction` of the space's maximum extent (with the pre-check when
  // the session has one).
  ob::SpaceInformationPtr spaceInformation(const std::shared_ptr<const JointSpace>& space, double fraction) {
    space->space()->registerDefaultProjection(std::make_shared<FirstJointsProjection>(space.get()));
    auto si = std::make_shared<ob::SpaceInformation>(space->space());
    si->setStateValidityChecker(std::make_shared<CallbackValidityChecker>(
        si, space, [this](const Eigen::VectorXd& q) { return valid(q); }));
    if (precheck) si->setMotionValidator(std::make_shared<PrecheckMotionValidator>(si, space, this));
    si->setStateValidityCheckingResolution(fraction);
    si->setup();
    return si;
  }

  // Space information over a space of its own (a state space owns its check resolution) with motions checked at
  // coarse_fraction. Made on first use, after the planner has been set up: nothing its setup draws from OMPL's seed
  // generator can then shift the planner's seeds, so a seeded plan's path before simplification is the same whatever
  // the simplification options.
  const ob::SpaceInformationPtr& coarseSpaceInformation(const std::vector<JointBounds>& joints) {
    std::call_once(coarse_once_, [&] {
      coarse_space_ = std::make_shared<JointSpace>(joints);
      coarse_si_ = spaceInformation(coarse_space_, coarse_fraction);
    });
    return coarse_si_;
  }

  std::string reason(const Eigen::VectorXd& q) const {
    if (!explain) return "";
    const std::string why = explain(q);
    return why.empty() ? "" : ": " + why;
  }

 private:
  std::once_flag coarse_once_;
  std::shared_ptr<const JointSpace> coarse_space_;
  ob::SpaceInformationPtr coarse_si_;
};

}  // namespace detail
}  // namespace sixdof_core
