#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "sixdof_core/planning.h"

namespace sixdof_core {
namespace {

// An axis-aligned box in joint space: the synthetic obstacle of these tests.
struct JointBox {
  std::string name;
  Eigen::VectorXd lower;
  Eigen::VectorXd upper;
  bool contains(const Eigen::VectorXd& q, double padding) const {
    return (q.array() >= lower.array() - padding).all() && (q.array() <= upper.array() + padding).all();
  }
};

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(values.size());
  int i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

struct World {
  std::vector<JointBounds> joints;
  std::vector<JointBox> boxes;
  // The planner sees padded boxes, as MoveIt pads links: discrete motion checks can cut an obstacle's corner
  // by up to half the check resolution, and the fine re-check below uses the true boxes.
  double padding = 0.01;

  // Box in the first two joints, spanning every other joint's full range.
  void addBox2(const std::string& name, double x0, double y0, double x1, double y1) {
    JointBox b{name, Eigen::VectorXd::Constant(joints.size(), -1e9), Eigen::VectorXd::Constant(joints.size(), 1e9)};
    b.lower.head<2>() << x0, y0;
    b.upper.head<2>() << x1, y1;
    boxes.push_back(b);
  }

  bool valid(const Eigen::VectorXd& q, double pad) const {
    for (const JointBox& b : boxes) {
      if (b.contains(q, pad)) return false;
    }
    return true;
  }

  std::string explain(const Eigen::VectorXd& q, double pad) const {
    for (const JointBox& b : boxes) {
      if (b.contains(q, pad)) return "inside box " + b.name;
    }
    return "";
  }

  PlanningProblem problem(const Eigen::VectorXd& start, const Eigen::VectorXd& goal) const {
    PlanningProblem p;
    p.joints = joints;
    p.is_valid = [this](const Eigen::VectorXd& q) { return valid(q, padding); };
    p.explain_invalid = [this](const Eigen::VectorXd& q) { return explain(q, padding); };
    p.start = start;
    p.joint_goal = JointGoal{goal, Eigen::VectorXd()};
    p.options.allowed_planning_time = 0.5;
    p.options.seed = 42;
    return p;
  }
};

World planar(double lo = -1.0, double hi = 1.0) {
  World w;
  w.joints = {{"x", lo, hi, false}, {"y", lo, hi, false}};
  return w;
}

// The plane with a pillar around the origin, for the start and goal checks.
World pillarWorld() {
  World w = planar();
  w.addBox2("pillar", -0.2, -0.2, 0.2, 0.2);
  return w;
}

World sixDof() {
  World w;
  for (int i = 1; i <= 6; ++i) w.joints.push_back({"joint" + std::to_string(i), -M_PI, M_PI, false});
  return w;
}

// Re-checks a path finely: continuous joint values (unwound), every point within bounds, every point of every
// segment (at 1e-3 max joint step) valid.
void expectValidPath(const World& w, const PlanningResult& r, double max_step = 0.0) {
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  ASSERT_GE(r.path.size(), 2u);
  for (std::size_t k = 0; k < r.path.size(); ++k) {
    const Eigen::VectorXd& q = r.path[k];
    for (std::size_t i = 0; i < w.joints.size(); ++i) {
      if (w.joints[i].continuous) continue;
      EXPECT_GE(q[i], w.joints[i].lower) << "point " << k;
      EXPECT_LE(q[i], w.joints[i].upper) << "point " << k;
    }
    if (k == 0) continue;
    const Eigen::VectorXd delta = q - r.path[k - 1];
    const double largest = delta.cwiseAbs().maxCoeff();
    if (max_step > 0.0) {
      EXPECT_LE(largest, max_step + 1e-9) << "segment " << k;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(largest / 1e-3)));
    for (int s = 0; s <= n; ++s) {
      const Eigen::VectorXd p = r.path[k - 1] + delta * (static_cast<double>(s) / n);
      Eigen::VectorXd wrapped = p;
      for (std::size_t i = 0; i < w.joints.size(); ++i) {
        if (w.joints[i].continuous) wrapped[i] = std::remainder(p[i], 2.0 * M_PI);
      }
      ASSERT_TRUE(w.valid(wrapped, 0.0)) << "segment " << k << " collides at " << p.transpose() << ": "
                                         << w.explain(wrapped, 0.0);
    }
  }
}

// A failed plan: its status, and a message that names the problem.
void expectFailure(const PlanningResult& r, PlanningStatus status, const std::string& needle) {
  EXPECT_EQ(r.status, status) << r.message;
  EXPECT_NE(r.message.find(needle), std::string::npos) << r.message;
}

class PlanningTest : public ::testing::Test {
 protected:
  void SetUp() override { ompl::msg::setLogLevel(ompl::msg::LOG_WARN); }
};

TEST_F(PlanningTest, EveryPlannerSolvesAnEasyProblem) {
  World w = planar();
  w.addBox2("middle", -0.3, -0.3, 0.3, 0.3);
  const std::vector<std::string> ids = availablePlannerIds();
  for (const char* required : {"RRTConnect", "RRTstar", "PRM", "BiTRRT", "KPIECE1"}) {
    EXPECT_NE(std::find(ids.begin(), ids.end(), required), ids.end()) << required;
  }
  for (const std::string& id : ids) {
    SCOPED_TRACE(id);
    PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.8, 0.8}));
    p.options.planner_id = id;
    p.options.allowed_planning_time = 0.3;  // the optimizing planners (RRTstar, PRMstar) use all of it
    const PlanningResult r = plan(p);
    expectValidPath(w, r);
    EXPECT_EQ(r.planner_id, id);
    EXPECT_TRUE(r.path.front().isApprox(p.start, 0.0));
    EXPECT_TRUE(r.path.back().isApprox(p.joint_goal->target, 0.0));
    EXPECT_GT(r.validity_checks, 0u);
    EXPECT_GT(r.path_length, 0.0);
  }
}

TEST_F(PlanningTest, NarrowPassage) {
  World w = planar();
  // A wall at x in [-0.05, 0.05] with a 0.06-wide gap at y in [0.40, 0.46].
  w.addBox2("wall_low", -0.05, -1.0, 0.05, 0.40);
  w.addBox2("wall_high", -0.05, 0.46, 0.05, 1.0);
  int solved = 0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.8, -0.8}));
    p.options.seed = seed;
    p.options.max_joint_step = 0.02;
    const PlanningResult r = plan(p);
    if (!r.ok()) continue;
    ++solved;
    expectValidPath(w, r, 0.02);
    bool through_gap = false;
    for (const Eigen::VectorXd& q : r.path) through_gap |= std::abs(q[0]) < 0.05 && q[1] > 0.40 && q[1] < 0.46;
    EXPECT_TRUE(through_gap);
  }
  EXPECT_GE(solved, 4);
}

TEST_F(PlanningTest, SixDofBoxesParallelAndSequentialAttempts) {
  World w = sixDof();
  // A slab across joint1 = 0, passable only with joint2 > 1.0 and joint3 < 0.
  w.addBox2("slab_low", -0.3, -M_PI, 0.3, 1.0);
  JointBox high{"slab_high", Eigen::VectorXd::Constant(6, -1e9), Eigen::VectorXd::Constant(6, 1e9)};
  high.lower.head<3>() << -0.3, 0.9, 0.0;
  high.upper.head<3>() << 0.3, M_PI, M_PI;
  w.boxes.push_back(high);
  const Eigen::VectorXd start = vec({-1.5, 0.0, 0.5, 0.3, -0.2, 1.0});
  const Eigen::VectorXd goal = vec({1.5, -0.5, 0.5, -0.3, 0.4, -1.0});
  for (bool parallel : {true, false}) {
    SCOPED_TRACE(parallel ? "parallel" : "sequential");
    PlanningProblem p = w.problem(start, goal);
    p.options.num_planning_attempts = 3;
    p.options.parallel_attempts = parallel;
    p.options.max_joint_step = 0.05;
    const PlanningResult r = plan(p);
    expectValidPath(w, r, 0.05);
    EXPECT_GE(r.solved_attempts, 1);
    EXPECT_TRUE(r.path.front().isApprox(start, 0.0));
    EXPECT_TRUE(r.path.back().isApprox(goal, 0.0));
  }
}

TEST_F(PlanningTest, SeededPlanningIsRepeatable) {
  World w = sixDof();
  w.addBox2("block", -0.5, -0.5, 0.5, 0.5);
  PlanningProblem p = w.problem(vec({-1.0, 0.0, 0, 0, 0, 0}), vec({1.0, 0.0, 0, 0, 0, 0}));
  p.options.seed = 7;
  const PlanningResult a = plan(p);
  const PlanningResult b = plan(p);
  ASSERT_TRUE(a.ok()) << a.message;
  ASSERT_EQ(a.path.size(), b.path.size());
  for (std::size_t k = 0; k < a.path.size(); ++k) EXPECT_TRUE(a.path[k].isApprox(b.path[k], 0.0)) << k;
}

TEST_F(PlanningTest, ContinuousJointTakesTheShortWayRound) {
  World w;
  w.joints = {{"wrist", 0.0, 0.0, true}, {"y", -1.0, 1.0, false}};
  // Blocks the way through 0, so the only route from -2.5 to 2.5 crosses +-pi.
  w.addBox2("block", -0.5, -1.0, 0.5, 1.0);
  PlanningProblem p = w.problem(vec({-2.5, 0.0}), vec({2.5, 0.0}));
  p.options.max_joint_step = 0.05;
  const PlanningResult r = plan(p);
  expectValidPath(w, r, 0.05);
  EXPECT_DOUBLE_EQ(r.path.front()[0], -2.5);
  // Unwound: the path ends at 2.5 - 2 pi, continuing below -pi instead of jumping.
  EXPECT_NEAR(r.path.back()[0], 2.5 - 2.0 * M_PI, 1e-9);
  EXPECT_LT(r.path_length, 2.0);
}

TEST_F(PlanningTest, InvalidStartIsReportedWithTheReason) {
  World w = pillarWorld();
  PlanningProblem p = w.problem(vec({0.0, 0.1}), vec({0.8, 0.8}));
  PlanningResult r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidStart, "inside box pillar");
  EXPECT_TRUE(r.path.empty());

  p.start = vec({1.5, 0.0});
  r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidStart, "x = 1.5 is outside its bounds");
}

TEST_F(PlanningTest, GoalInCollision) {
  World w = pillarWorld();
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.1, 0.0}));
  PlanningResult r = plan(p);
  expectFailure(r, PlanningStatus::kGoalInCollision, "inside box pillar");

  p.joint_goal.reset();
  p.goal_states = {vec({0.1, 0.0}), vec({-0.1, 0.1})};
  r = plan(p);
  expectFailure(r, PlanningStatus::kGoalInCollision, "inside box pillar");
}

TEST_F(PlanningTest, GoalOutOfBoundsIsInvalidGoal) {
  World w = planar();
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.5, 1.2}));
  const PlanningResult r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidGoal, "y = 1.2");
}

TEST_F(PlanningTest, JointGoalToleranceReachesAValidStateNearAnInvalidTarget) {
  World w = pillarWorld();
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.15, 0.0}));
  p.joint_goal->tolerance = vec({0.2, 0.2});
  const PlanningResult r = plan(p);
  expectValidPath(w, r);
  EXPECT_LE((r.path.back() - p.joint_goal->target).cwiseAbs().maxCoeff(), 0.2 + 1e-12);
}

TEST_F(PlanningTest, GoalStatesReachOneOfTheValidOnes) {
  World w = pillarWorld();
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0, 0}));
  p.joint_goal.reset();
  p.goal_states = {vec({0.0, 0.0}), vec({0.7, 0.6}), vec({0.6, -0.7})};
  const PlanningResult r = plan(p);
  expectValidPath(w, r);
  EXPECT_TRUE(r.path.back().isApprox(p.goal_states[1], 0.0) || r.path.back().isApprox(p.goal_states[2], 0.0));
}

TEST_F(PlanningTest, SampledGoals) {
  World w = pillarWorld();
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0, 0}));
  p.joint_goal.reset();

  p.sampled_goal = SampledGoal{[](Eigen::VectorXd*) { return false; }};
  PlanningResult r = plan(p);
  EXPECT_EQ(r.status, PlanningStatus::kNoIkSolution) << r.message;

  p.sampled_goal = SampledGoal{[](Eigen::VectorXd* q) {
    *q = vec({0.1, 0.1});
    return true;
  }};
  r = plan(p);
  expectFailure(r, PlanningStatus::kGoalInCollision, "inside box pillar");

  // An "IK" that fails every other call and alternates between two solutions of a pose.
  int calls = 0;
  p.sampled_goal = SampledGoal{[&calls](Eigen::VectorXd* q) {
    ++calls;
    if (calls % 2) return false;
    *q = (calls % 4 == 0) ? vec({0.7, 0.7}) : vec({0.1, 0.1});
    return true;
  }};
  r = plan(p);
  expectValidPath(w, r);
  EXPECT_TRUE(r.path.back().isApprox(vec({0.7, 0.7}), 0.0));

  p.sampled_goal = SampledGoal{[](Eigen::VectorXd* q) {
    *q = vec({0.7, 0.7, 0.0});
    return true;
  }};
  r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidRequest, "has 3 values for 2 joints");
}

TEST_F(PlanningTest, UnreachableGoalTimesOut) {
  World w = planar();
  // The goal (0.5, 0.5) sits inside a closed ring of four walls.
  w.addBox2("ring_w", 0.3, 0.3, 0.35, 0.7);
  w.addBox2("ring_e", 0.65, 0.3, 0.7, 0.7);
  w.addBox2("ring_s", 0.3, 0.3, 0.7, 0.35);
  w.addBox2("ring_n", 0.3, 0.65, 0.7, 0.7);
  PlanningProblem p = w.problem(vec({-0.8, -0.8}), vec({0.5, 0.5}));
  p.options.allowed_planning_time = 0.1;
  const PlanningResult r = plan(p);
  EXPECT_EQ(r.status, PlanningStatus::kTimeout) << r.message;
  EXPECT_TRUE(r.path.empty());
}

TEST_F(PlanningTest, MalformedRequestsAreRejected) {
  World w = planar();
  const PlanningProblem good = w.problem(vec({-0.8, -0.8}), vec({0.8, 0.8}));

  PlanningProblem p = good;
  p.options.planner_id = "RRTFast";
  PlanningResult r = plan(p);
  EXPECT_EQ(r.status, PlanningStatus::kInvalidRequest);
  for (const char* id : {"RRTFast", "RRTConnect", "RRTstar", "PRM", "BiTRRT", "KPIECE1"}) {
    EXPECT_NE(r.message.find(id), std::string::npos) << r.message;
  }

  p = good;
  p.options.planner_id = "RRTConnectkConfigDefault";
  EXPECT_EQ(plan(p).status, PlanningStatus::kSuccess);

  p = good;
  p.start = vec({NAN, 0.0});
  r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidRequest, "NaN");

  p = good;
  p.joint_goal->target = vec({0.0, NAN});
  EXPECT_EQ(plan(p).status, PlanningStatus::kInvalidRequest);

  p = good;
  p.start = vec({0.0, 0.0, 0.0});
  EXPECT_EQ(plan(p).status, PlanningStatus::kInvalidRequest);

  p = good;
  p.joints[1].lower = 2.0;
  r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidRequest, "joint y has invalid bounds");

  p = good;
  p.is_valid = nullptr;
  EXPECT_EQ(plan(p).status, PlanningStatus::kInvalidRequest);

  p = good;
  p.goal_states = {vec({0.5, 0.5})};
  EXPECT_EQ(plan(p).status, PlanningStatus::kInvalidRequest);

  p = good;
  p.options.allowed_planning_time = 0.0;
  EXPECT_EQ(plan(p).status, PlanningStatus::kInvalidRequest);

  for (double factor : {0.5, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
    p = good;
    p.options.simplify_coarse_factor = factor;
    r = plan(p);
    EXPECT_EQ(r.status, PlanningStatus::kInvalidRequest) << factor;
    EXPECT_NE(r.message.find("simplify_coarse_factor"), std::string::npos) << r.message;
  }

  p = good;
  p.options.planner_params = {{"no_such_param", "1"}};
  r = plan(p);
  expectFailure(r, PlanningStatus::kInvalidRequest, "no_such_param");

  p = good;
  p.options.planner_params = {{"range", "0.1"}};
  EXPECT_EQ(plan(p).status, PlanningStatus::kSuccess);
}

TEST_F(PlanningTest, ValidityResolutionIsHonoured) {
  World w = planar();
  w.addBox2("thin_wall", 0.2, -0.5, 0.22, 0.5);
  // A 1.0-long straight segment checked every 0.45 steps over the 0.02-thick wall without touching it.
  PlanningProblem p = w.problem(vec({-0.5, 0.0}), vec({0.5, 0.0}));
  p.options.longest_valid_segment_length = 0.45;
  p.options.simplify = false;
  PlanningResult r = plan(p);
  ASSERT_TRUE(r.ok()) << r.message;
  bool crossed_wall = false;
  for (std::size_t k = 1; k < r.path.size(); ++k) crossed_wall |= r.path[k - 1][0] < 0.2 && r.path[k][0] > 0.22;
  EXPECT_TRUE(crossed_wall);

  p.options.longest_valid_segment_length = 0.005;
  r = plan(p);
  expectValidPath(w, r);
}

// Around one square, the shortest way goes along one side: the simplified paths of twenty seeds come close to it,
// however the planner's path went (with the shortcuts of plan(): at most 14 % longer at the median, 27 % at most;
// with OMPL's shortcutPath, one try per vertex, up to 54 %).
TEST_F(PlanningTest, SimplifiedPathsComeCloseToTheShortestWayAroundAnObstacle) {
  World w = planar();
  w.addBox2("block", -0.3, -0.3, 0.3, 0.3);
  const double half = 0.3 + w.padding;
  const double shortest = 2.0 * std::hypot(0.9 - half, half) + 2.0 * half;
  std::vector<double> lengths;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    PlanningProblem p = w.problem(vec({-0.9, 0.0}), vec({0.9, 0.0}));
    p.options.seed = seed;
    const PlanningResult r = plan(p);
    expectValidPath(w, r);
    lengths.push_back(r.path_length);
  }
  std::sort(lengths.begin(), lengths.end());
  EXPECT_GE(lengths.front(), shortest - 1e-6);
  EXPECT_LE(lengths[lengths.size() / 2], 1.2 * shortest);
  EXPECT_LE(lengths.back(), 1.35 * shortest);
}

TEST_F(PlanningTest, CoarseSimplificationIsRecheckedAtThePlanningResolution) {
  World w = planar();
  // A 2 mm wall (6 mm padded) between start and goal with a gap at the top: the only way round is through the
  // gap. Planning checks every 1 mm; the coarse pass checks every 14 mm (its cap, 0.005 of the extent 2.83),
  // so shortcuts across the wall can look free to it: the re-check at the planning resolution must catch
  // them and simplify again.
  w.padding = 0.002;
  w.addBox2("thin_wall", 0.2, -1.0, 0.202, 0.6);
  PlanningProblem p = w.problem(vec({-0.5, 0.0}), vec({0.5, 0.0}));
  p.options.longest_valid_segment_length = 0.001;
  p.options.simplify_coarse_factor = 100.0;
  PlanningResult r = plan(p);
  expectValidPath(w, r);
  EXPECT_TRUE(r.simplification_fallback);
  EXPECT_GT(r.simplification_time, 0.0);
  EXPECT_LE(r.simplification_time, r.planning_time);

  // A factor of 4 (whether or not its coarse result passes the re-check here).
  p.options.simplify_coarse_factor = 4.0;
  r = plan(p);
  expectValidPath(w, r);

  p.options.simplify_coarse_factor = 1.0;
  const PlanningResult fine = plan(p);
  expectValidPath(w, fine);
  EXPECT_FALSE(fine.simplification_fallback);
  // Both detour through the gap (y > 0.6) and are about as short (simplification quality is kept).
  EXPECT_NEAR(r.path_length, fine.path_length, 0.1 * fine.path_length);

  // At MoveIt's default resolution (0.005 of the extent) there is no coarser pass: a factor of 4 then plans
  // exactly as factor 1 (same seed, same checks, same path).
  p.options.longest_valid_segment_length = 0.0;
  p.options.longest_valid_segment_fraction = 0.005;
  const PlanningResult capped = plan(p);
  p.options.simplify_coarse_factor = 4.0;
  const PlanningResult defaulted = plan(p);
  ASSERT_TRUE(capped.ok()) << capped.message;
  ASSERT_TRUE(defaulted.ok()) << defaulted.message;
  EXPECT_EQ(defaulted.validity_checks, capped.validity_checks);
  ASSERT_EQ(defaulted.path.size(), capped.path.size());
  for (std::size_t k = 0; k < capped.path.size(); ++k) EXPECT_TRUE(defaulted.path[k].isApprox(capped.path[k]));

  p.options.simplify = false;
  r = plan(p);
  EXPECT_EQ(r.simplification_time, 0.0);
  EXPECT_FALSE(r.simplification_fallback);
}

}  // namespace
}  // namespace sixdof_core
