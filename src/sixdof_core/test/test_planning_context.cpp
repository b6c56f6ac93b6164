#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/planning_context.h"
#include "test_description.h"
#include "test_planning_table_top.h"

namespace sixdof_core {
namespace {

using sixdof_test::TableTop;

// Link padding (m) of the scene the planner sees; the re-check uses the true scene. Motion checks every
// 0.005 rad (joint-space distance) move no point of the arm more than about 5 mm, so a check interval can cut
// at most about half that into an obstacle's corner: inside the padding.
constexpr double kPadding = 0.005;

class PlanningContextTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const std::string description = sixdof_test::descriptionDir();
    t_ = sixdof_test::makeTableTop(description + "/urdf/sixdof.urdf", SIXDOF_TEST_DATA_DIR "/sixdof.srdf",
                                   description, kPadding);
    options_.seed = 3;
    options_.allowed_planning_time = 2.0;
    options_.longest_valid_segment_length = 0.005;
    options_.max_joint_step = 0.05;
  }

  RobotState stateAt(const Eigen::VectorXd& arm) const {
    RobotState s(t_.model);
    s.setGroupPositions("arm", arm);
    return s;
  }

  // Re-checks the path in the true (unpadded) scene at 0.002 rad steps, and its bounds and continuity.
  void expectCollisionFree(const RobotState& start, const std::vector<Eigen::VectorXd>& path, double max_step) {
    ASSERT_GE(path.size(), 2u);
    EXPECT_TRUE(path.front().isApprox(start.groupPositions("arm"), 0.0));
    RobotState s = start;
    for (std::size_t k = 0; k < path.size(); ++k) {
      s.setGroupPositions("arm", path[k]);
      EXPECT_TRUE(s.satisfiesBounds()) << "point " << k << ": " << path[k].transpose();
      if (k == 0) continue;
      const Eigen::VectorXd delta = path[k] - path[k - 1];
      if (max_step > 0.0) {
        EXPECT_LE(delta.cwiseAbs().maxCoeff(), max_step + 1e-9) << "segment " << k;
      }
      const int n = std::max(1, static_cast<int>(std::ceil(delta.cwiseAbs().maxCoeff() / 0.002)));
      for (int i = 0; i <= n; ++i) {
        s.setGroupPositions("arm", path[k - 1] + delta * (static_cast<double>(i) / n));
        ASSERT_FALSE(t_.colliding(s)) << "segment " << k << " collides at " << s.groupPositions("arm").transpose()
                                      << ": " << t_.context->explainFn(start)(s.groupPositions("arm"));
      }
    }
  }

  Eigen::Isometry3d tipPose(const Eigen::VectorXd& arm) const { return t_.ik->chain().forward(arm); }

  TableTop t_;
  PlanningOptions options_;
};

TEST_F(PlanningContextTest, PickAndPlaceMovesAroundThePost) {
  const RobotState home = stateAt(Eigen::VectorXd::Zero(6));
  ASSERT_FALSE(t_.colliding(home));
  PoseGoalOptions pose_goal;

  const Eigen::Isometry3d above_cube = t_.tipFor(TableTop::topDown(0.40, -0.15, 0.12));
  PlanningResult r = t_.context->planToPose(home, above_cube, pose_goal, options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  expectCollisionFree(home, r.path, options_.max_joint_step);
  PoseError err = poseError(tipPose(r.path.back()), above_cube);
  EXPECT_LT(err.position, 1e-4);
  EXPECT_LT(err.orientation, 1e-3);

  // The post stands between the pick and the place location.
  const RobotState at_cube = stateAt(r.path.back());
  const Eigen::Isometry3d above_place = t_.tipFor(TableTop::topDown(0.40, 0.20, 0.12, 0.3));
  r = t_.context->planToPose(at_cube, above_place, pose_goal, options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  expectCollisionFree(at_cube, r.path, options_.max_joint_step);
  err = poseError(tipPose(r.path.back()), above_place);
  EXPECT_LT(err.position, 1e-4);
  EXPECT_LT(err.orientation, 1e-3);
  EXPECT_GT(r.validity_checks, 0u);
}

TEST_F(PlanningContextTest, JointNamedAndPositionGoals) {
  const RobotState start = stateAt((Eigen::VectorXd(6) << 0.8, 0.4, 0.6, 0.0, 0.5, 0.0).finished());
  ASSERT_FALSE(t_.colliding(start));

  const Eigen::VectorXd goal = (Eigen::VectorXd(6) << -0.9, 0.5, 0.3, 0.5, 0.8, -1.0).finished();
  ASSERT_FALSE(t_.colliding(stateAt(goal)));
  PlanningResult r = t_.context->planToJoints(start, goal, 0.0, options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  expectCollisionFree(start, r.path, options_.max_joint_step);
  EXPECT_TRUE(r.path.back().isApprox(goal, 0.0));

  std::string named;
  for (const GroupState& s : t_.model->groupStates()) {
    if (s.group == "arm") named = s.name;
  }
  ASSERT_FALSE(named.empty()) << "the SRDF has no named state of the arm";
  r = t_.context->planToNamed(start, named, 0.0, options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  RobotState named_state = start;
  named_state.setToNamedState("arm", named);
  EXPECT_TRUE(r.path.back().isApprox(named_state.groupPositions("arm"), 0.0));

  r = t_.context->planToNamed(start, "no_such_pose", 0.0, options_);
  EXPECT_EQ(r.status, PlanningStatus::kInvalidRequest);
  EXPECT_NE(r.message.find(named), std::string::npos) << r.message;

  const Eigen::Vector3d position(0.30, 0.25, 0.25);
  r = t_.context->planToPosition(start, position, PoseGoalOptions(), options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  expectCollisionFree(start, r.path, options_.max_joint_step);
  EXPECT_LT((tipPose(r.path.back()).translation() - position).norm(), 1e-4);
}

TEST_F(PlanningContextTest, InvalidStartsAndGoalsAreReported) {
  const RobotState home = stateAt(Eigen::VectorXd::Zero(6));
  // Upper arm tilted far forward, forearm pointing back down: the wrist ends below the table top.
  const RobotState in_table = stateAt((Eigen::VectorXd(6) << 0.0, 1.9, 0.3, 0.0, 0.0, 0.0).finished());
  ASSERT_TRUE(t_.colliding(in_table));
  PlanningResult r = t_.context->planToJoints(in_table, Eigen::VectorXd::Zero(6), 0.0, options_);
  EXPECT_EQ(r.status, PlanningStatus::kInvalidStart);
  EXPECT_NE(r.message.find("table"), std::string::npos) << r.message;

  // The tcp inside the post: IK solves it, every solution collides.
  r = t_.context->planToPose(home, t_.tipFor(TableTop::topDown(0.42, 0.03, 0.15)), PoseGoalOptions(), options_);
  EXPECT_EQ(r.status, PlanningStatus::kGoalInCollision) << r.message;
  EXPECT_NE(r.message.find("post"), std::string::npos) << r.message;

  r = t_.context->planToPose(home, t_.tipFor(TableTop::topDown(1.5, 0.0, 0.2)), PoseGoalOptions(), options_);
  EXPECT_EQ(r.status, PlanningStatus::kNoIkSolution) << r.message;
}

// With the closed-form solver a pose goal's states are its IK solutions, each handed out once: the first nearest
// the start, then the others nearest-first.
TEST_F(PlanningContextTest, AnalyticPoseGoalsTryEverySolutionOnce) {
  const auto* analytic = dynamic_cast<const AnalyticIkSolver*>(t_.ik.get());
  ASSERT_NE(analytic, nullptr) << t_.ik_note;
  const RobotState home = stateAt(Eigen::VectorXd::Zero(6));
  // Every solution of a tcp inside the post collides: each is sampled, once.
  const Eigen::Isometry3d in_post = t_.tipFor(TableTop::topDown(0.42, 0.03, 0.15));
  const std::size_t solutions = analytic->solveAll(in_post, Eigen::VectorXd::Zero(6)).solutions.size();
  ASSERT_GT(solutions, 1u);
  PlanningResult r = t_.context->planToPose(home, in_post, PoseGoalOptions(), options_);
  EXPECT_EQ(r.status, PlanningStatus::kGoalInCollision) << r.message;
  EXPECT_NE(r.message.find("all " + std::to_string(solutions) + " sampled goal states are invalid"), std::string::npos)
      << r.message;
  // A reachable pose ends on one of its solutions.
  const Eigen::Isometry3d above = t_.tipFor(TableTop::topDown(0.30, -0.30, 0.25));
  r = t_.context->planToPose(home, above, PoseGoalOptions(), options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : analytic->solveAll(above, Eigen::VectorXd::Zero(6)).solutions) {
    nearest = std::min(nearest, (q - r.path.back()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(nearest, 1e-6);
}

TEST_F(PlanningContextTest, CartesianDescentStopsAtTheTable) {
  const RobotState home = stateAt(Eigen::VectorXd::Zero(6));
  const PlanningResult to_above =
      t_.context->planToPose(home, t_.tipFor(TableTop::topDown(0.30, -0.30, 0.25)), PoseGoalOptions(), options_);
  ASSERT_EQ(to_above.status, PlanningStatus::kSuccess) << to_above.message;
  const RobotState above = stateAt(to_above.path.back());

  const Eigen::Isometry3d low = t_.tipFor(TableTop::topDown(0.30, -0.30, 0.10));
  JumpThreshold jump;
  jump.relative = 5.0;
  CartesianPathResult c = t_.context->cartesianPath(above, {low}, 0.005, jump, true);
  ASSERT_EQ(c.status, CartesianStatus::kSuccess) << c.message;
  EXPECT_DOUBLE_EQ(c.fraction, 1.0);
  expectCollisionFree(above, c.path, 0.0);
  const Eigen::Vector3d a = tipPose(c.path.front()).translation();
  const Eigen::Vector3d b = low.translation();
  for (const Eigen::VectorXd& q : c.path) {
    const Eigen::Vector3d p = tipPose(q).translation();
    const Eigen::Vector3d d = (b - a).normalized();
    EXPECT_LT(((p - a) - (p - a).dot(d) * d).norm(), 1e-4);
  }

  // Into the table: the path stops where the padded hand reaches it.
  const Eigen::Isometry3d below = t_.tipFor(TableTop::topDown(0.30, -0.30, -0.05));
  c = t_.context->cartesianPath(above, {below}, 0.005, jump, true);
  EXPECT_EQ(c.status, CartesianStatus::kInCollision) << c.message;
  EXPECT_GT(c.fraction, 0.3);
  EXPECT_LT(c.fraction, 1.0);
  EXPECT_NE(c.message.find("table"), std::string::npos) << c.message;
  expectCollisionFree(above, c.path, 0.0);
}

TEST_F(PlanningContextTest, PathConstraintsHoldAlongThePath) {
  const RobotState start = stateAt((Eigen::VectorXd(6) << 0.8, 0.4, 0.6, 0.0, 0.5, 0.0).finished());
  const Eigen::VectorXd goal = (Eigen::VectorXd(6) << -0.9, 0.5, 0.3, 0.5, 0.8, -1.0).finished();
  // joint4 kept in [-0.1, 0.6] and link6's origin kept above z = 0.15 (a state condition) all along the path.
  PathConstraints constraints;
  constraints.joint_bounds.push_back({"joint4", -0.1, 0.6, false});
  constraints.state = [](const RobotState& s) { return s.linkTransform("link6").translation().z() > 0.15; };
  constraints.explain = [](const RobotState&) { return std::string("link6 below z = 0.15"); };
  t_.context->setPathConstraints(constraints);
  const PlanningResult r = t_.context->planToJoints(start, goal, 0.0, options_);
  ASSERT_EQ(r.status, PlanningStatus::kSuccess) << r.message;
  expectCollisionFree(start, r.path, options_.max_joint_step);
  RobotState s = start;
  for (std::size_t k = 1; k < r.path.size(); ++k) {
    const Eigen::VectorXd delta = r.path[k] - r.path[k - 1];
    const int n = std::max(1, static_cast<int>(std::ceil(delta.cwiseAbs().maxCoeff() / 0.002)));
    for (int i = 0; i <= n; ++i) {
      const Eigen::VectorXd q = r.path[k - 1] + delta * (static_cast<double>(i) / n);
      EXPECT_GE(q[3], -0.1 - 1e-9);
      EXPECT_LE(q[3], 0.6 + 1e-9);
      s.setGroupPositions("arm", q);
      EXPECT_GT(s.linkTransform("link6").translation().z(), 0.15 - 2e-3) << "segment " << k;
    }
  }
  // A goal outside the joint range violates the constraints, and says so.
  Eigen::VectorXd outside = goal;
  outside[3] = 1.0;
  EXPECT_NE(t_.context->pathConstraintViolation(start, outside).find("joint4"), std::string::npos);
  EXPECT_THROW(t_.context->setPathConstraints({{{"finger1_joint", 0.0, 0.01, false}}, {}, {}}), std::invalid_argument);
  EXPECT_THROW(t_.context->setPathConstraints({{{"joint2", 3.0, 4.0, false}}, {}, {}}), std::invalid_argument);
}

}  // namespace
}  // namespace sixdof_core
