#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// A serial chain of a RobotModel from a base link to a tip link: the pose of the tip in the base frame
// as a function of the chain's moving joints. Fixed joints are folded into constant transforms.
class KinematicChain {
 public:
  // Throws RobotModelError if a link is unknown, tip is not below base, or the chain has a mimic joint.
  KinematicChain(const RobotModel& model, const std::string& base_link, const std::string& tip_link);
  // The chain of an SRDF group: its <chain>, or the serial path spanned by its active joints (from the
  // parent link of the first to the child link of the last). Throws RobotModelError naming the problem.
  static KinematicChain forGroup(const RobotModel& model, const std::string& group);

  const std::string& baseLink() const { return base_link_; }
  const std::string& tipLink() const { return tip_link_; }
  size_t dof() const { return joints_.size(); }
  const std::vector<std::string>& jointNames() const { return joint_names_; }
  const JointModel& joint(size_t i) const { return joints_[i]; }
  Eigen::VectorXd lowerLimits() const;
  Eigen::VectorXd upperLimits() const;
  // Middle of every joint's range (0 for continuous joints).
  Eigen::VectorXd midPositions() const;
  // Within limits (continuous joints always are).
  bool withinLimits(const Eigen::VectorXd& q, double tolerance = 0.0) const;

  // Tip pose in the base frame. q has dof() entries.
  Eigen::Isometry3d forward(const Eigen::VectorXd& q) const;
  // Geometric Jacobian in the base frame, reference point at the tip origin: rows 0-2 linear velocity,
  // rows 3-5 angular velocity.
  Matrix6Xd jacobian(const Eigen::VectorXd& q) const;
  // Both at once (the Jacobian needs the same transforms).
  void forwardAndJacobian(const Eigen::VectorXd& q, Eigen::Isometry3d* tip, Matrix6Xd* jacobian) const;

  // Constant transform before moving joint i (from the previous joint's frame, or the base for i = 0);
  // tipOffset() follows the last moving joint.
  const Eigen::Isometry3d& jointOffset(size_t i) const { return offsets_[i]; }
  const Eigen::Isometry3d& tipOffset() const { return tip_offset_; }

 private:
  std::string base_link_;
  std::string tip_link_;
  std::vector<JointModel> joints_;
  std::vector<std::string> joint_names_;
  std::vector<Eigen::Isometry3d> offsets_;
  Eigen::Isometry3d tip_offset_ = Eigen::Isometry3d::Identity();
};

// Rotation from roll, pitch, yaw about the fixed x, y, z axes (tf2's setRPY): R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw);
// The inverse (tf2's getRPY): roll and yaw in [-pi, pi], pitch in [-pi/2, pi/2]; yaw = 0 at pitch +-pi/2.
Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& rotation);
Eigen::Isometry3d poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw);

// Pose error between two poses, both in the same frame: translation distance and rotation angle.
struct PoseError {
  double position = 0.0;
  double orientation = 0.0;
};
PoseError poseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace sixdof_core
