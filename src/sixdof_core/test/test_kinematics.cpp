#include <gtest/gtest.h>

#include <random>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/robot_model.h"
#include "test_models.h"

namespace sixdof_core {
namespace {

// The provisional URDF writes pi/2 as 1.5708: hand-computed poses agree to this.
constexpr double kHandTolerance = 1e-5;

Eigen::VectorXd arm(double q1, double q2, double q3, double q4, double q5, double q6) {
  Eigen::VectorXd q(6);
  q << q1, q2, q3, q4, q5, q6;
  return q;
}

Eigen::Matrix3d ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
Eigen::Matrix3d rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }

struct HandPose {
  Eigen::VectorXd q;
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;
};

// link6 poses worked out by hand from the joint table in docs/design.md.
std::vector<HandPose> handPoses() {
  const double h = M_PI / 2;
  return {
      // Zero: upper arm up, forearm along +x, flange z along +x, flange x down.
      {arm(0, 0, 0, 0, 0, 0), {0.38, 0, 0.6}, ry(h)},
      // Base turned a quarter: everything along +y.
      {arm(h, 0, 0, 0, 0, 0), {0, 0.38, 0.6}, rz(h) * ry(h)},
      // Shoulder forward: upper arm along +x from (0,0,0.3), forearm pointing down.
      {arm(0, h, 0, 0, 0, 0), {0.3, 0, -0.08}, ry(M_PI)},
      // Elbow up: forearm vertical, flange pointing up.
      {arm(0, 0, -h, 0, 0, 0), {0, 0, 0.98}, Eigen::Matrix3d::Identity()},
      // Wrist pitched down: the flange 0.08 below the wrist centre (0.3, 0, 0.6).
      {arm(0, 0, 0, 0, h, 0), {0.3, 0, 0.52}, ry(M_PI)},
      // Forearm roll then wrist pitch: the flange swings to +y.
      {arm(0, 0, 0, h, h, 0), {0.3, 0.08, 0.6}, rx(h) * ry(h) * ry(h)},
      // Flange roll only turns link6 about its own z.
      {arm(0, 0, 0, 0, 0, h), {0.38, 0, 0.6}, ry(h) * rz(h)},
  };
}

TEST(ForwardKinematics, ArmMatchesHandComputedPoses) {
  const auto model = armModel();
  RobotState state(model);
  const KinematicChain chain = KinematicChain::forGroup(*model, "arm");
  for (const auto& pose : handPoses()) {
    state.setGroupPositions("arm", pose.q);
    const Eigen::Isometry3d& link6 = state.linkTransform("link6");
    EXPECT_TRUE(link6.translation().isApprox(pose.position, kHandTolerance) ||
                (link6.translation() - pose.position).norm() < kHandTolerance)
        << "q = " << pose.q.transpose() << "\nlink6 at " << link6.translation().transpose();
    EXPECT_LT((link6.linear() - pose.rotation).norm(), kHandTolerance) << "q = " << pose.q.transpose();
    const Eigen::Isometry3d from_chain = chain.forward(pose.q);
    EXPECT_LT((from_chain.matrix() - link6.matrix()).norm(), 1e-12);
  }
  // tcp is on link6's z axis, in front of the flange.
  state.setGroupPositions("arm", arm(0.3, -0.2, 0.5, 1.0, -0.7, 2.0));
  const Eigen::Vector3d tcp_in_link6 =
      state.linkTransform("link6").inverse() * state.linkTransform("tcp").translation();
  EXPECT_NEAR(tcp_in_link6.x(), 0.0, 1e-12);
  EXPECT_NEAR(tcp_in_link6.y(), 0.0, 1e-12);
  EXPECT_GT(tcp_in_link6.z(), 0.0);
}

TEST(ForwardKinematics, ChainAgreesWithRobotStateOnRandomConfigurations) {
  for (const auto& model : {armModel(), urModel()}) {
    const std::string group = model->name() == "sixdof" ? "arm" : "manipulator";
    const KinematicChain chain = KinematicChain::forGroup(*model, group);
    RobotState state(model);
    std::mt19937_64 rng(7);
    for (int i = 0; i < 200; ++i) {
      Eigen::VectorXd q(chain.dof());
      for (size_t j = 0; j < chain.dof(); ++j) {
        q[j] = std::uniform_real_distribution<double>(chain.joint(j).limits.lower, chain.joint(j).limits.upper)(rng);
      }
      state.setGroupPositions(group, q);
      const Eigen::Isometry3d expected = state.linkTransform(chain.baseLink()).inverse() *
                                         state.linkTransform(chain.tipLink());
      EXPECT_LT((chain.forward(q).matrix() - expected.matrix()).norm(), 1e-12);
    }
  }
}

TEST(Jacobian, MatchesFiniteDifferences) {
  for (const auto& model : {armModel(), urModel()}) {
    const KinematicChain chain(*model, model->rootLink(), model->name() == "sixdof" ? "link6" : "tool0");
    std::mt19937_64 rng(11);
    for (int i = 0; i < 50; ++i) {
      Eigen::VectorXd q(chain.dof());
      for (size_t j = 0; j < chain.dof(); ++j) q[j] = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
      const Matrix6Xd jacobian = chain.jacobian(q);
      const Eigen::Isometry3d tip = chain.forward(q);
      const double step = 1e-7;
      for (size_t j = 0; j < chain.dof(); ++j) {
        Eigen::VectorXd moved = q;
        moved[j] += step;
        const Eigen::Isometry3d tip_moved = chain.forward(moved);
        const Eigen::Vector3d linear = (tip_moved.translation() - tip.translation()) / step;
        const Eigen::AngleAxisd turn(tip_moved.linear() * tip.linear().transpose());
        const Eigen::Vector3d angular = turn.angle() * turn.axis() / step;
        EXPECT_LT((jacobian.block<3, 1>(0, j) - linear).norm(), 1e-5);
        EXPECT_LT((jacobian.block<3, 1>(3, j) - angular).norm(), 1e-5);
      }
    }
  }
}

// RobotState::jacobian of a point on a link against finite differences of the state's link transforms.
void expectStateJacobianMatchesFiniteDifferences(const RobotModelConstPtr& model, const std::string& group,
                                                 const std::string& link, const Eigen::Vector3d& point) {
  RobotState state(model);
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20; ++i) {
    Eigen::VectorXd q = state.groupPositions(group);
    for (Eigen::Index j = 0; j < q.size(); ++j) q[j] = std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
    state.setGroupPositions(group, q);
    const Matrix6Xd jacobian = state.jacobian(group, link, point);
    ASSERT_EQ(jacobian.cols(), q.size());
    const Eigen::Isometry3d pose = state.linkTransform(link);
    const double step = 1e-7;
    for (Eigen::Index j = 0; j < q.size(); ++j) {
      RobotState moved = state;
      Eigen::VectorXd q_moved = q;
      q_moved[j] += step;
      moved.setGroupPositions(group, q_moved);
      const Eigen::Isometry3d pose_moved = moved.linkTransform(link);
      const Eigen::Vector3d linear = (pose_moved * point - pose * point) / step;
      const Eigen::AngleAxisd turn(pose_moved.linear() * pose.linear().transpose());
      const Eigen::Vector3d angular = turn.angle() * turn.axis() / step;
      EXPECT_LT((jacobian.block<3, 1>(0, j) - linear).norm(), 1e-5) << group << " " << link << " column " << j;
      EXPECT_LT((jacobian.block<3, 1>(3, j) - angular).norm(), 1e-5) << group << " " << link << " column " << j;
    }
  }
}

TEST(Jacobian, RobotStateOfAnyLinkAndPoint) {
  const auto model = armModel();
  expectStateJacobianMatchesFiniteDifferences(model, "arm", "link6", Eigen::Vector3d::Zero());
  expectStateJacobianMatchesFiniteDifferences(model, "arm", "tcp", Eigen::Vector3d(0.01, -0.02, 0.03));
  expectStateJacobianMatchesFiniteDifferences(model, "arm", "finger2", Eigen::Vector3d(0.0, 0.01, 0.02));
  // Joints after the link do not move it.
  expectStateJacobianMatchesFiniteDifferences(model, "arm", "link3", Eigen::Vector3d(0.1, 0.0, 0.0));
  // Continuous and prismatic joints, and a mimic joint that moves its source's column.
  const auto kinds = RobotModel::fromFiles(kDataDir + "/joint_kinds.urdf", kDataDir + "/joint_kinds.srdf");
  expectStateJacobianMatchesFiniteDifferences(kinds, "arm", "sensor_frame", Eigen::Vector3d(0.02, 0.0, 0.0));
  expectStateJacobianMatchesFiniteDifferences(kinds, "gripper", "right_finger", Eigen::Vector3d::Zero());

  // The arm's tip: the chain's Jacobian (the root link is the chain's base).
  RobotState state(model);
  Eigen::VectorXd q(6);
  q << 0.3, -0.4, 0.9, 1.2, -0.6, 2.0;
  state.setGroupPositions("arm", q);
  const KinematicChain chain = KinematicChain::forGroup(*model, "arm");
  EXPECT_LT((state.jacobian("arm", "link6") - chain.jacobian(q)).norm(), 1e-12);
  EXPECT_TRUE(state.jacobian("arm", "link3").rightCols(3).isZero());
  EXPECT_THROW(state.jacobian("nope", "link6"), std::invalid_argument);
  EXPECT_THROW(state.jacobian("arm", "nope"), std::out_of_range);
}

TEST(KinematicChain, GroupsAndLimits) {
  const auto model = urModel();
  const KinematicChain wrist = KinematicChain::forGroup(*model, "wrist");
  EXPECT_EQ(wrist.baseLink(), "forearm_link");
  EXPECT_EQ(wrist.tipLink(), "wrist_3_link");
  EXPECT_EQ(wrist.dof(), 3u);
  const KinematicChain manipulator = KinematicChain::forGroup(*model, "manipulator");
  EXPECT_EQ(manipulator.dof(), 6u);
  EXPECT_DOUBLE_EQ(manipulator.midPositions()[0], 0.0);
  Eigen::VectorXd q = manipulator.midPositions();
  q[0] = 100.0;  // continuous
  EXPECT_TRUE(manipulator.withinLimits(q));
  q[2] = 3.2;
  EXPECT_FALSE(manipulator.withinLimits(q));
  EXPECT_THROW(KinematicChain::forGroup(*model, "nope"), RobotModelError);

  const auto arm_model = armModel();
  // finger2_joint mimics finger1_joint: not a chain the kinematics supports.
  EXPECT_THROW(KinematicChain(*arm_model, "palm", "finger2"), RobotModelError);
  EXPECT_THROW(KinematicChain::forGroup(*arm_model, "gripper"), RobotModelError);
  EXPECT_THROW(KinematicChain(*arm_model, "link6", "link1"), RobotModelError);
}

TEST(Rpy, FixedAxesLikeTf2SetRpy) {
  // tf2 setRPY(r, p, y) == Rz(y) * Ry(p) * Rx(r); roll alone turns about x, and so on.
  const Eigen::Matrix3d r = rotationFromRpy(0.3, -0.2, 1.1);
  EXPECT_LT((r - rz(1.1) * ry(-0.2) * rx(0.3)).norm(), 1e-15);
  const Eigen::Isometry3d pose = poseFromXyzRpy(1, 2, 3, M_PI / 2, 0, 0);
  EXPECT_TRUE(pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_LT((pose.linear() * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  const PoseError error = poseError(pose, poseFromXyzRpy(1, 2, 3.5, M_PI / 2 + 0.25, 0, 0));
  EXPECT_NEAR(error.position, 0.5, 1e-12);
  EXPECT_NEAR(error.orientation, 0.25, 1e-12);
}

}  // namespace
}  // namespace sixdof_core
