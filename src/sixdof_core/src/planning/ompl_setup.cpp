#include "ompl_setup.h"

#include <deque>

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

namespace sixdof_core {
namespace detail {

namespace og = ompl::geometric;

double shortestAngle(double from, double to) {
  double d = std::fmod(to - from, kTwoPi);
  if (d > M_PI) d -= kTwoPi;
  if (d < -M_PI) d += kTwoPi;
  return d;
}

double jointDelta(const JointBounds& joint, double from, double to) {
  return joint.continuous ? shortestAngle(from, to) : to - from;
}

namespace {

template <typename T>
ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si) {
  return std::make_shared<T>(si);
}

}  // namespace

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

PrecheckMotionValidator::Motion PrecheckMotionValidator::motion(const ob::State* s1, const ob::State* s2) const {
  const std::vector<JointBounds>& joints = joint_space_->joints();
  Motion m{s1, s2, std::max(1, static_cast<int>(si_->getStateSpace()->validSegmentCount(s1, s2))),
           joint_space_->fromOmpl(s1), {}};
  const Eigen::VectorXd to = joint_space_->fromOmpl(s2);
  m.step.resize(m.from.size());
  for (std::size_t i = 0; i < joints.size(); ++i) m.step[i] = jointDelta(joints[i], m.from[i], to[i]);
  return m;
}

PrecheckMotionValidator::Around PrecheckMotionValidator::precheck(const Motion& m, int k, int reach) const {
  if (!session_->precheckPays()) return Around();  // is_valid takes state k (and the bisection goes on without it)
  const double cap = static_cast<double>(reach) / m.n;
  thread_local Eigen::VectorXd q;  // no allocation per call
  q = m.from + m.step * (static_cast<double>(k) / m.n);
  // Half a state's tolerance: the proof may lose at most one state to it.
  const MotionPrecheck p = session_->prove(q, m.step, cap, 0.5 / m.n);
  Around around;
  if (p.proven > 0.0) {
    around.proven = p.proven >= cap ? reach : static_cast<int>(std::floor(p.proven * m.n));
  } else {
    const double unprovable = std::max<double>(kUnprovenNeighbours, std::floor(p.unprovable * m.n));
    around.unprovable = static_cast<int>(std::min<double>(reach, unprovable));
  }
  return around;
}

bool PrecheckMotionValidator::stateValid(const Motion& m, int k, ob::State* test) const {
  // Straight to is_valid: the state is within bounds (as both ends are).
  joint_space_->space()->interpolate(m.s1, m.s2, static_cast<double>(k) / m.n, test);
  return session_->valid(joint_space_->fromOmpl(test));
}

int PrecheckMotionValidator::firstInvalid(const Motion& m) const {
  // s2 out of bounds is invalid however free it is (the states between are inside the bounds box when both ends are).
  const int last = si_->satisfiesBounds(m.s2) ? m.n : m.n - 1;
  ob::State* test = si_->allocState();
  int invalid = last + 1;
  // States 1..k are valid; s1 (k = 0) is, by the contract of checkMotion. `unproven`: states after k that go to
  // is_valid without asking the pre-check (it proves nothing there).
  for (int k = 0, unproven = 0; k < last;) {
    if (unproven == 0) {
      const Around around = precheck(m, k, last - k);
      if (around.proven > 0) {
        session_->precheck_states += around.proven;
        k += around.proven;
        continue;
      }
      unproven = std::max(1, around.unprovable);
    }
    if (!stateValid(m, k + 1, test)) {
      invalid = k + 1;
      break;
    }
    ++k;
    --unproven;
  }
  si_->freeState(test);
  return invalid;
}

bool PrecheckMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  bool valid = si_->satisfiesBounds(s2);
  const Motion m = motion(s1, s2);
  ob::State* test = si_->allocState();
  std::deque<std::pair<int, int>> runs;  // runs of states not yet known valid, middles first (OMPL's order)
  if (valid) runs.emplace_back(1, m.n);
  while (valid && !runs.empty()) {
    const auto [lo, hi] = runs.front();
    runs.pop_front();
    if (hi - lo < kShortRun) {  // cheaper by is_valid alone
      for (int k = lo; valid && k <= hi; ++k) valid = stateValid(m, k, test);
      continue;
    }
    const int mid = (lo + hi) / 2;
    const Around around = precheck(m, mid, std::max(mid - lo, hi - mid));
    // The states the pre-check proves, or else those it cannot, which is_valid checks here (the middle first).
    const int side = around.proven >= 0 ? around.proven : around.unprovable;
    const int below = std::max(lo, mid - side), above = std::min(hi, mid + side);
    if (around.proven >= 0) {
      session_->precheck_states += above - below + 1;
    } else {
      for (int k = mid; valid && k <= above; ++k) valid = stateValid(m, k, test);
      for (int k = mid - 1; valid && k >= below; --k) valid = stateValid(m, k, test);
    }
    if (lo < below) runs.emplace_back(lo, below - 1);
    if (above < hi) runs.emplace_back(above + 1, hi);
  }
  si_->freeState(test);
  ++(valid ? valid_ : invalid_);
  return valid;
}

bool PrecheckMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                          std::pair<ob::State*, double>& last_valid) const {
  const Motion m = motion(s1, s2);
  const int invalid = firstInvalid(m);
  if (invalid > m.n) {
    ++valid_;
    return true;
  }
  last_valid.second = static_cast<double>(invalid - 1) / m.n;
  if (last_valid.first) joint_space_->space()->interpolate(s1, s2, last_valid.second, last_valid.first);
  ++invalid_;
  return false;
}

std::string canonicalPlannerId(const std::string& id) {
  static const std::string kMoveItSuffix = "kConfigDefault";
  if (id.size() > kMoveItSuffix.size() && id.compare(id.size() - kMoveItSuffix.size(), std::string::npos,
                                                     kMoveItSuffix) == 0) {
    return id.substr(0, id.size() - kMoveItSuffix.size());
  }
  return id;
}

}  // namespace detail
}  // namespace sixdof_core
