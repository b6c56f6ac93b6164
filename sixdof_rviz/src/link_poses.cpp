#include "sixdof_rviz/link_poses.h"

#include <stdexcept>

namespace sixdof_rviz {
namespace {

Eigen::Isometry3d toEigen(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  out.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                     .normalized()
                     .toRotationMatrix();
  return out;
}

}  // namespace

LinkPoses::LinkPoses(urdf::ModelInterfaceSharedPtr model) : model_(std::move(model)) {
  if (!model_ || !model_->getRoot()) throw std::invalid_argument("LinkPoses: URDF model without a root link");
  root_link_ = model_->getRoot()->name;
}

double LinkPoses::jointValue(const urdf::Joint& joint, const JointValues& values) const {
  if (joint.mimic) {
    auto master = model_->getJoint(joint.mimic->joint_name);
    if (!master) throw std::invalid_argument("URDF: joint '" + joint.name + "' mimics unknown joint");
    return joint.mimic->multiplier * jointValue(*master, values) + joint.mimic->offset;
  }
  auto it = values.find(joint.name);
  return it == values.end() ? 0.0 : it->second;
}

void LinkPoses::descend(const urdf::Link& link, const Eigen::Isometry3d& pose, const JointValues& values,
                        LinkPoseMap* out) const {
  (*out)[link.name] = pose;
  for (const auto& child : link.child_links) {
    const urdf::Joint& joint = *child->parent_joint;
    Eigen::Isometry3d child_pose = pose * toEigen(joint.parent_to_joint_origin_transform);
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        child_pose.rotate(Eigen::AngleAxisd(jointValue(joint, values), axis.normalized()));
        break;
      case urdf::Joint::PRISMATIC:
        child_pose.translate(axis.normalized() * jointValue(joint, values));
        break;
      default:
        break;  // fixed (floating/planar joints are drawn at their origin)
    }
    descend(*child, child_pose, values, out);
  }
}

LinkPoseMap LinkPoses::compute(const JointValues& values) const {
  LinkPoseMap out;
  descend(*model_->getRoot(), Eigen::Isometry3d::Identity(), values, &out);
  return out;
}

}  // namespace sixdof_rviz
