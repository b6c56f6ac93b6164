// The sphere pre-check of motions (PlanningContext::precheckFn, CollisionScene::precheckMotion) in planning: what it
// proves holds under FCL, and planning with it returns paths that FCL accepts, the same paths as without it.
#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sixdof_core/planning_context.h"
#include "test_description.h"
#include "test_planning_table_top.h"

namespace sixdof_core {
namespace {

using sixdof_test::TableTop;

constexpr double kPadding = 0.005;

// Seeded clutter: boxes of 2-8 cm anywhere over the table, up to 0.45 m high.
std::vector<WorldObject> clutter(std::mt19937* rng, int count) {
  std::uniform_real_distribution<double> x(-0.1, 0.7), y(-0.5, 0.5), z(0.02, 0.45), size(0.02, 0.08), yaw(-3.0, 3.0);
  std::vector<WorldObject> objects;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d at(x(*rng), y(*rng), z(*rng));
    if (at.head<2>().norm() < 0.18) continue;  // not into the arm's base
    WorldObject o = sixdof_test::tableTopObject("clutter_" + std::to_string(i), Shape::Type::kBox, at,
                                                {size(*rng), size(*rng), size(*rng)});
    o.pose.linear() = Eigen::AngleAxisd(yaw(*rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    objects.push_back(o);
  }
  return objects;
}

// The arm with the description's SRDF: its "Never" pairs leave out the wrist's neighbours, which are always closer
// to each other than the spheres' overshoot (with the test SRDF, adjacent pairs only, the pre-check proves nothing
// and plan() stops asking it).
TableTop tableTop(const std::vector<WorldObject>& extra = {}) {
  const std::string description = sixdof_test::descriptionDir();
  return sixdof_test::makeTableTop(description + "/urdf/sixdof.urdf", description + "/config/sixdof.srdf", description,
                                   kPadding, extra);
}

Eigen::VectorXd randomArm(const PlanningContext& context, std::mt19937* rng) {
  Eigen::VectorXd q(context.joints().size());
  for (std::size_t i = 0; i < context.joints().size(); ++i) {
    const JointBounds& b = context.joints()[i];
    q[i] = std::uniform_real_distribution<double>(b.lower, b.upper)(*rng);
  }
  return q;
}

// True when every state of the path, at most `step` rad apart on every joint, is free in the true (unpadded) scene.
bool fclValid(const TableTop& t, const std::vector<Eigen::VectorXd>& path, double step, std::string* where) {
  RobotState s(t.model);
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Eigen::VectorXd delta = path[k] - path[k - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(delta.cwiseAbs().maxCoeff() / step)));
    for (int i = 0; i <= n; ++i) {
      s.setGroupPositions("arm", path[k - 1] + delta * (static_cast<double>(i) / n));
      if (t.colliding(s)) {
        *where = "segment " + std::to_string(k) + " at " + std::to_string(i) + "/" + std::to_string(n);
        return false;
      }
    }
  }
  return true;
}

class PrecheckPlanningTest : public ::testing::Test {
 protected:
  void SetUp() override { ompl::msg::setLogLevel(ompl::msg::LOG_WARN); }
};

// The table top with 30 boxes of clutter, and the planner's validity check and pre-check from its default state.
struct Cluttered {
  explicit Cluttered(std::mt19937* rng)
      : t(tableTop(clutter(rng, 30))),
        valid(t.context->validityFn(RobotState(t.model))),
        precheck(t.context->precheckFn(RobotState(t.model))) {}

  TableTop t;
  JointValidityFn valid;
  MotionPrecheckFn precheck;
};

// What the pre-check proves from random states along random joint steps holds under FCL (the planner's validity
// check, padded scene) at every state within the proven stretch, either way; where it proves nothing, it proves
// nothing within the stretch it calls unprovable either.
TEST_F(PrecheckPlanningTest, ProofsHoldUnderFcl) {
  std::mt19937 rng(7);
  const auto& [t, valid, precheck] = Cluttered(&rng);
  std::uniform_real_distribution<double> length(0.05, 1.5);
  int proven = 0, unprovable = 0;
  for (int k = 0; k < 600; ++k) {
    const Eigen::VectorXd q = randomArm(*t.context, &rng);
    Eigen::VectorXd step = randomArm(*t.context, &rng) - q;
    step *= length(rng) / step.norm();
    const MotionPrecheck p = precheck(q, step, 1.0, 0.0);
    ASSERT_GE(p.proven, 0.0);
    ASSERT_LE(p.proven, 1.0);
    if (p.proven > 0.0) {
      ++proven;
      for (int i = -20; i <= 20; ++i) {
        const double w = p.proven * i / 20.0;
        ASSERT_TRUE(valid(q + w * step)) << "state " << k << ": proven " << p.proven << ", collides at " << w;
      }
    } else if (p.unprovable > 0.0) {
      ++unprovable;
      for (const double w : {-0.5 * p.unprovable, 0.5 * p.unprovable}) {
        EXPECT_EQ(precheck(q + w * step, step, 1.0, 0.0).proven, 0.0) << "state " << k << " at " << w;
      }
    }
  }
  EXPECT_GT(proven, 150) << "the pre-check proves too little to be tested";
  EXPECT_GT(unprovable, 20);
}

// A single state: with a zero step the pre-check proves free states only, and most clearly free ones.
TEST_F(PrecheckPlanningTest, ZeroStepProvesFreeStatesOnly) {
  std::mt19937 rng(11);
  const auto& [t, valid, precheck] = Cluttered(&rng);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(t.context->joints().size()));
  int free = 0, proven = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::VectorXd q = randomArm(*t.context, &rng);
    const bool is_free = valid(q);
    const bool is_proven = precheck(q, zero, 1.0, 0.0).proven > 0.0;
    ASSERT_TRUE(is_free || !is_proven) << "state " << k << " collides but was proven free";
    free += is_free;
    proven += is_proven;
  }
  EXPECT_GT(proven, free / 2) << proven << " of " << free << " free states proven";
}

// A seeded random problem: the table top with 6-15 boxes of clutter, a free start, and a pose goal (even problems)
// or a joint goal (odd ones), planned at 0.005 rad with the pre-check.
struct RandomProblem {
  RandomProblem(int problem, std::mt19937* rng)
      : index(problem), t(tableTop(clutter(rng, 6 + problem % 10))), start(t.model) {
    const JointValidityFn valid = t.context->validityFn(start);
    Eigen::VectorXd q = randomArm(*t.context, rng);
    while (!valid(q)) q = randomArm(*t.context, rng);
    start.setGroupPositions("arm", q);
    options.seed = static_cast<std::uint32_t>(problem + 1);
    options.allowed_planning_time = 0.5;  // bounds the unsolvable ones
    options.longest_valid_segment_length = 0.005;
    options.max_joint_step = 0.05;
    std::uniform_real_distribution<double> x(0.2, 0.55), y(-0.4, 0.4), z(0.08, 0.35), yaw(-1.5, 1.5);
    tcp = TableTop::topDown(x(*rng), y(*rng), z(*rng), yaw(*rng));
    goal = randomArm(*t.context, rng);
    while (!valid(goal)) goal = randomArm(*t.context, rng);
  }

  PlanningResult plan(const PlanningOptions& o) const {
    return index % 2 == 0 ? t.context->planToPose(start, t.tipFor(tcp), PoseGoalOptions(), o)
                          : t.context->planToJoints(start, goal, 0.0, o);
  }

  int index;
  TableTop t;
  RobotState start;
  PlanningOptions options;
  Eigen::Isometry3d tcp;
  Eigen::VectorXd goal;
};

// Seeded random problems: every path returned with the pre-check is free under FCL at 0.001 rad, and planning
// without the pre-check returns the same path (it changes no motion's answer).
TEST_F(PrecheckPlanningTest, RandomProblemsGiveFclValidPathsAndTheSamePathsAsWithoutIt) {
  std::mt19937 rng(2024);
  int solved = 0, compared = 0;
  for (int problem = 0; problem < 40; ++problem) {
    RandomProblem p(problem, &rng);
    const PlanningResult r = p.plan(p.options);
    if (!r.ok()) continue;
    ++solved;
    EXPECT_GT(r.precheck_states, 0u) << "problem " << problem;
    std::string where;
    EXPECT_TRUE(fclValid(p.t, r.path, 0.001, &where)) << "problem " << problem << ": " << where;

    if (problem % 3 != 0) continue;
    p.options.precheck = false;
    const PlanningResult exact = p.plan(p.options);
    ASSERT_TRUE(exact.ok()) << "problem " << problem << ": " << exact.message;
    ASSERT_EQ(exact.path.size(), r.path.size()) << "problem " << problem;
    for (std::size_t k = 0; k < r.path.size(); ++k) {
      EXPECT_LE((exact.path[k] - r.path[k]).cwiseAbs().maxCoeff(), 1e-12) << "problem " << problem << ", point " << k;
    }
    EXPECT_LT(r.validity_checks, exact.validity_checks) << "problem " << problem;
    ++compared;
  }
  EXPECT_GE(solved, 24) << "too few problems solved for the check to mean anything";
  EXPECT_GE(compared, 8);
}

// The simplification (vertex reduction and shortcutting, checked coarser first or at the planning resolution
// throughout): the same seeded plan simplified either way is free under FCL at 0.001 rad and no longer than the
// planner's unsimplified path, and simplification shortens most of them.
TEST_F(PrecheckPlanningTest, SimplifiedPathsAreFclValidAndNoLongerThanTheRawPath) {
  std::mt19937 rng(77);
  int solved = 0, shortened = 0;
  for (int problem = 0; problem < 20; ++problem) {
    RandomProblem p(problem, &rng);
    p.options.simplify = false;
    const PlanningResult raw = p.plan(p.options);
    if (!raw.ok()) continue;
    ++solved;
    p.options.simplify = true;
    for (const double factor : {4.0, 1.0}) {
      p.options.simplify_coarse_factor = factor;
      const PlanningResult r = p.plan(p.options);
      ASSERT_TRUE(r.ok()) << "problem " << problem << ", factor " << factor << ": " << r.message;
      std::string where;
      EXPECT_TRUE(fclValid(p.t, r.path, 0.001, &where))
          << "problem " << problem << ", factor " << factor << ": " << where;
      EXPECT_LE(r.path_length, raw.path_length + 1e-9) << "problem " << problem << ", factor " << factor;
      shortened += r.path_length < 0.95 * raw.path_length;
    }
  }
  EXPECT_GE(solved, 12) << "too few problems solved for the check to mean anything";
  EXPECT_GE(shortened, solved) << "simplification shortened too few paths";
}

}  // namespace
}  // namespace sixdof_core
