#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sixdof_core/cartesian_path.h"

namespace sixdof_core {
namespace {

// A synthetic 6-joint "robot" whose IK is exact: joints 0-2 are the tip position, joints 3-5 its rotation vector.
Eigen::Isometry3d gantryFk(const Eigen::VectorXd& q) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = q.head<3>();
  const Eigen::Vector3d rv = q.tail<3>();
  if (rv.norm() > 0.0) pose.linear() = Eigen::AngleAxisd(rv.norm(), rv.normalized()).toRotationMatrix();
  return pose;
}

bool gantryIk(const Eigen::Isometry3d& target, const Eigen::VectorXd& /*seed*/, Eigen::VectorXd* out) {
  out->resize(6);
  out->head<3>() = target.translation();
  const Eigen::AngleAxisd aa(target.linear());
  out->tail<3>() = aa.angle() * aa.axis();
  return true;
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() << x, y, z;
  p.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return p;
}

CartesianPathRequest request(const std::vector<Eigen::Isometry3d>& waypoints) {
  CartesianPathRequest r;
  r.start = Eigen::VectorXd::Zero(6);
  r.waypoints = waypoints;
  r.eef_step = 0.01;
  r.fk = gantryFk;
  r.ik = gantryIk;
  r.is_valid = [](const Eigen::VectorXd&) { return true; };
  r.prismatic = {true, true, true, false, false, false};
  return r;
}

double distanceToLine(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = (b - a).normalized();
  return ((p - a) - (p - a).dot(d) * d).norm();
}

TEST(CartesianPath, StraightLineWithPerfectIk) {
  const Eigen::Isometry3d goal = pose(0.3, 0.1, -0.05, 0.6);
  const CartesianPathResult r = computeCartesianPath(request({goal}));
  ASSERT_EQ(r.status, CartesianStatus::kSuccess) << r.message;
  EXPECT_DOUBLE_EQ(r.fraction, 1.0);
  // The line is 0.3202 m long: ceil(32.02) = 33 steps of at most eef_step, plus the start.
  ASSERT_EQ(r.path.size(), 34u);
  EXPECT_TRUE(r.path.front().isApprox(Eigen::VectorXd::Zero(6), 0.0));
  EXPECT_TRUE(gantryFk(r.path.back()).isApprox(goal, 1e-12));
  const double length = goal.translation().norm();
  for (std::size_t k = 0; k < r.path.size(); ++k) {
    const Eigen::Isometry3d tip = gantryFk(r.path[k]);
    EXPECT_LT(distanceToLine(tip.translation(), Eigen::Vector3d::Zero(), goal.translation()), 1e-12) << k;
    // Orientation follows the slerp: the yaw is proportional to the distance travelled.
    const double t = tip.translation().norm() / length;
    EXPECT_NEAR(Eigen::AngleAxisd(tip.linear()).angle(), 0.6 * t, 1e-9) << k;
    if (k > 0) {
      EXPECT_LE((tip.translation() - gantryFk(r.path[k - 1]).translation()).norm(), 0.01 + 1e-12);
    }
  }
}

TEST(CartesianPath, PassesThroughEveryWaypoint) {
  const std::vector<Eigen::Isometry3d> waypoints = {pose(0.1, 0.0, 0.0, 0.0), pose(0.1, 0.2, 0.0, 0.3),
                                                    pose(0.0, 0.2, 0.1, -0.2)};
  const CartesianPathResult r = computeCartesianPath(request(waypoints));
  ASSERT_EQ(r.status, CartesianStatus::kSuccess) << r.message;
  EXPECT_DOUBLE_EQ(r.fraction, 1.0);
  for (const Eigen::Isometry3d& w : waypoints) {
    bool reached = false;
    for (const Eigen::VectorXd& q : r.path) reached |= gantryFk(q).isApprox(w, 1e-12);
    EXPECT_TRUE(reached) << w.translation().transpose();
  }
}

TEST(CartesianPath, PureRotationIsSplitByTheRotationStep) {
  CartesianPathRequest req = request({pose(0.0, 0.0, 0.0, 1.0)});
  CartesianPathResult r = computeCartesianPath(req);
  ASSERT_EQ(r.status, CartesianStatus::kSuccess) << r.message;
  EXPECT_EQ(r.path.size(), 2u);  // no translation: one step, as MoveIt without a rotation step
  req.eef_rotation_step = 0.1;
  r = computeCartesianPath(req);
  ASSERT_EQ(r.status, CartesianStatus::kSuccess) << r.message;
  EXPECT_EQ(r.path.size(), 11u);
}

TEST(CartesianPath, IkFailureMidwayGivesTheAchievedFraction) {
  CartesianPathRequest req = request({pose(0.3, 0.0, 0.0, 0.0)});
  req.ik = [](const Eigen::Isometry3d& target, const Eigen::VectorXd& seed, Eigen::VectorXd* out) {
    return target.translation().x() <= 0.15 + 1e-9 && gantryIk(target, seed, out);
  };
  CartesianPathResult r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kIkFailed);
  EXPECT_NEAR(r.fraction, 0.5, 1e-9);
  EXPECT_EQ(r.path.size(), 16u);
  EXPECT_NEAR(gantryFk(r.path.back()).translation().x(), 0.15, 1e-9);

  // Two equal-weight segments, failing halfway through the second: 0.5 + 0.5 * 0.5.
  req.waypoints = {pose(0.1, 0.0, 0.0, 0.0), pose(0.2, 0.0, 0.0, 0.0)};
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kIkFailed);
  EXPECT_NEAR(r.fraction, 0.75, 1e-9);
}

// The same tip rotation expressed by the other rotation vector (angle - 2 pi): a configuration flip.
bool flippingIk(const Eigen::Isometry3d& target, const Eigen::VectorXd& seed, Eigen::VectorXd* out) {
  gantryIk(target, seed, out);
  if (target.translation().x() > 0.2 + 1e-9) {
    const Eigen::Vector3d rv = out->tail<3>();
    out->tail<3>() = rv.normalized() * (rv.norm() - 2.0 * M_PI);
  }
  return true;
}

TEST(CartesianPath, JumpsAreDetected) {
  CartesianPathRequest req = request({pose(0.3, 0.0, 0.0, 0.5)});
  req.ik = flippingIk;
  CartesianPathResult r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kSuccess) << "no threshold: the jump is kept, as in MoveIt";
  EXPECT_DOUBLE_EQ(r.fraction, 1.0);

  req.jump_threshold.relative = 2.0;
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kJumpDetected) << r.message;
  EXPECT_NEAR(r.fraction, 2.0 / 3.0, 1e-9);
  EXPECT_NE(r.message.find("relative"), std::string::npos) << r.message;
  for (std::size_t k = 1; k < r.path.size(); ++k) EXPECT_LT((r.path[k] - r.path[k - 1]).cwiseAbs().maxCoeff(), 0.1);

  req.jump_threshold = JumpThreshold{0.0, 1.0, 0.0};
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kJumpDetected) << r.message;
  EXPECT_NEAR(r.fraction, 2.0 / 3.0, 1e-9);
  EXPECT_NE(r.message.find("absolute"), std::string::npos) << r.message;

  // A prismatic threshold tighter than eef_step cuts at the first step.
  req.jump_threshold = JumpThreshold{0.0, 0.0, 0.005};
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kJumpDetected) << r.message;
  EXPECT_EQ(r.path.size(), 1u);
  EXPECT_DOUBLE_EQ(r.fraction, 0.0);
}

TEST(CartesianPath, RelativeJumpTestNeedsEnoughPoints) {
  CartesianPathRequest req = request({pose(0.03, 0.0, 0.0, 0.0)});
  req.jump_threshold.relative = 2.0;
  const CartesianPathResult r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kSuccess);
  EXPECT_NE(r.message.find("relative jump test skipped: only 4 points"), std::string::npos) << r.message;
}

TEST(CartesianPath, CollisionMidwayStopsThePath) {
  CartesianPathRequest req = request({pose(0.3, 0.0, 0.0, 0.0)});
  req.is_valid = [](const Eigen::VectorXd& q) { return q[0] < 0.095 || q[0] > 0.125; };
  req.explain_invalid = [](const Eigen::VectorXd&) { return std::string("tip hits the wall"); };
  CartesianPathResult r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kInCollision);
  EXPECT_NEAR(r.fraction, 0.09 / 0.3, 1e-9);
  EXPECT_NE(r.message.find("tip hits the wall"), std::string::npos) << r.message;
  for (const Eigen::VectorXd& q : r.path) EXPECT_TRUE(req.is_valid(q));

  req.avoid_collisions = false;
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kSuccess);
  EXPECT_DOUBLE_EQ(r.fraction, 1.0);

  req.avoid_collisions = true;
  req.start[0] = 0.11;
  r = computeCartesianPath(req);
  EXPECT_EQ(r.status, CartesianStatus::kInvalidStart);
  EXPECT_DOUBLE_EQ(r.fraction, 0.0);
  EXPECT_TRUE(r.path.empty());
}

TEST(CartesianPath, MalformedRequestsAreRejected) {
  const CartesianPathRequest good = request({pose(0.1, 0.0, 0.0, 0.0)});
  auto expectRejected = [](const CartesianPathRequest& req, const std::string& words) {
    const CartesianPathResult r = computeCartesianPath(req);
    EXPECT_EQ(r.status, CartesianStatus::kInvalidRequest);
    EXPECT_NE(r.message.find(words), std::string::npos) << r.message;
    EXPECT_TRUE(r.path.empty());
  };
  CartesianPathRequest req = good;
  req.eef_step = 0.0;
  expectRejected(req, "eef_step");
  req = good;
  req.waypoints.clear();
  expectRejected(req, "no waypoints");
  req = good;
  req.waypoints[0].translation().x() = NAN;
  expectRejected(req, "waypoint 0");
  req = good;
  req.start[2] = NAN;
  expectRejected(req, "start state");
  req = good;
  req.ik = nullptr;
  expectRejected(req, "IK");
  req = good;
  req.jump_threshold.revolute = -1.0;
  expectRejected(req, "jump thresholds");
  req = good;
  req.prismatic = {true};
  expectRejected(req, "prismatic");
  req = good;
  req.ik = [](const Eigen::Isometry3d&, const Eigen::VectorXd&, Eigen::VectorXd* out) {
    *out = Eigen::VectorXd::Zero(2);
    return true;
  };
  expectRejected(req, "malformed");
}

TEST(CartesianPath, MoveItArgumentOrder) {
  const CartesianPathResult r =
      computeCartesianPath(Eigen::VectorXd::Zero(6), {pose(0.05, 0.0, 0.0, 0.0)}, 0.01, JumpThreshold{}, true, gantryFk,
                           gantryIk, [](const Eigen::VectorXd&) { return true; });
  EXPECT_EQ(r.status, CartesianStatus::kSuccess);
  EXPECT_EQ(r.path.size(), 6u);
}
}  // namespace
}  // namespace sixdof_core
