#include "sixdof_core/kinematics.h"

#include <algorithm>
#include <cmath>

namespace sixdof_core {

KinematicChain::KinematicChain(const RobotModel& model, const std::string& base_link, const std::string& tip_link)
    : base_link_(base_link), tip_link_(tip_link) {
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();
  for (int j : model.chainJoints(base_link, tip_link)) {
    const JointModel& joint = model.joints()[j];
    if (joint.type == JointType::kFixed) {
      pending = pending * joint.origin;
      continue;
    }
    if (joint.mimic) {
      throw RobotModelError("chain " + base_link + " -> " + tip_link + " contains mimic joint '" + joint.name +
                            "', which kinematic chains do not support");
    }
    offsets_.push_back(pending * joint.origin);
    pending = Eigen::Isometry3d::Identity();
    joints_.push_back(joint);
    joint_names_.push_back(joint.name);
  }
  tip_offset_ = pending;
}

KinematicChain KinematicChain::forGroup(const RobotModel& model, const std::string& group_name) {
  const JointGroup* group = model.findGroup(group_name);
  if (!group) throw RobotModelError("unknown group '" + group_name + "'");
  if (group->isChain()) return KinematicChain(model, group->chain_base, group->chain_tip);
  if (group->active_joints.empty()) throw RobotModelError("group '" + group_name + "' has no active joints");
  const std::string base = model.joint(group->active_joints.front()).parent_link;
  const std::string tip = model.joint(group->active_joints.back()).child_link;
  KinematicChain chain(model, base, tip);
  size_t moving = 0;
  for (const auto& joint : group->joints) moving += model.joint(joint).type != JointType::kFixed;
  if (chain.jointNames() != group->active_joints || moving != chain.dof()) {
    throw RobotModelError("group '" + group_name + "' is not a serial chain: its joints are not the path " + base +
                          " -> " + tip);
  }
  return chain;
}

Eigen::VectorXd KinematicChain::lowerLimits() const {
  Eigen::VectorXd q(dof());
  for (size_t i = 0; i < dof(); ++i) q[i] = joints_[i].limits.lower;
  return q;
}

Eigen::VectorXd KinematicChain::upperLimits() const {
  Eigen::VectorXd q(dof());
  for (size_t i = 0; i < dof(); ++i) q[i] = joints_[i].limits.upper;
  return q;
}

Eigen::VectorXd KinematicChain::midPositions() const {
  Eigen::VectorXd q(dof());
  for (size_t i = 0; i < dof(); ++i) {
    q[i] = joints_[i].limits.bounded ? 0.5 * (joints_[i].limits.lower + joints_[i].limits.upper) : 0.0;
  }
  return q;
}

bool KinematicChain::withinLimits(const Eigen::VectorXd& q, double tolerance) const {
  for (size_t i = 0; i < dof(); ++i) {
    const auto& limits = joints_[i].limits;
    if (limits.bounded && (q[i] < limits.lower - tolerance || q[i] > limits.upper + tolerance)) return false;
  }
  return true;
}

Eigen::Isometry3d KinematicChain::forward(const Eigen::VectorXd& q) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < dof(); ++i) {
    t = t * offsets_[i];
    if (joints_[i].type == JointType::kPrismatic) {
      t.translate(q[i] * joints_[i].axis);
    } else {
      t.rotate(Eigen::AngleAxisd(q[i], joints_[i].axis));
    }
  }
  return t * tip_offset_;
}

Matrix6Xd KinematicChain::jacobian(const Eigen::VectorXd& q) const {
  Eigen::Isometry3d tip;
  Matrix6Xd j;
  forwardAndJacobian(q, &tip, &j);
  return j;
}

void KinematicChain::forwardAndJacobian(const Eigen::VectorXd& q, Eigen::Isometry3d* tip, Matrix6Xd* jacobian) const {
  jacobian->resize(6, dof());
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  // Joint axes and origins in the base frame; the linear part needs the tip position, known at the end,
  // so the linear rows hold the joint origins until then.
  for (size_t i = 0; i < dof(); ++i) {
    t = t * offsets_[i];
    const Eigen::Vector3d axis = t.linear() * joints_[i].axis;
    jacobian->block<3, 1>(0, i) = t.translation();
    jacobian->block<3, 1>(3, i) = axis;
    if (joints_[i].type == JointType::kPrismatic) {
      t.translate(q[i] * joints_[i].axis);
    } else {
      t.rotate(Eigen::AngleAxisd(q[i], joints_[i].axis));
    }
  }
  *tip = t * tip_offset_;
  for (size_t i = 0; i < dof(); ++i) {
    const Eigen::Vector3d axis = jacobian->block<3, 1>(3, i);
    if (joints_[i].type == JointType::kPrismatic) {
      jacobian->block<3, 1>(0, i) = axis;
      jacobian->block<3, 1>(3, i).setZero();
    } else {
      jacobian->block<3, 1>(0, i) = axis.cross(tip->translation() - jacobian->block<3, 1>(0, i));
    }
  }
}

Eigen::Matrix3d rotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& r) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): r(2, 0) = -sin(pitch); at |pitch| = pi/2 only roll - yaw (or roll + yaw) is
  // defined, and yaw = 0 is taken.
  const double pitch = std::asin(std::max(-1.0, std::min(1.0, -r(2, 0))));
  if (std::abs(r(2, 0)) > 1.0 - 1e-12) {
    return Eigen::Vector3d(std::atan2(-r(1, 2), r(1, 1)), pitch, 0.0);
  }
  return Eigen::Vector3d(std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0)));
}

Eigen::Isometry3d poseFromXyzRpy(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  pose.linear() = rotationFromRpy(roll, pitch, yaw);
  return pose;
}

PoseError poseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  PoseError error;
  error.position = (a.translation() - b.translation()).norm();
  error.orientation = Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
  return error;
}

}  // namespace sixdof_core
