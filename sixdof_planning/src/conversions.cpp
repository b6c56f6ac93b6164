#include "sixdof_planning/conversions.h"

namespace sixdof_planning {

Eigen::Isometry3d poseToEigen(const geometry_msgs::Pose& pose) {
  Eigen::Quaterniond q(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  q.normalize();
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = q.toRotationMatrix();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return result;
}

geometry_msgs::Pose eigenToPose(const Eigen::Isometry3d& pose) {
  geometry_msgs::Pose msg;
  msg.position.x = pose.translation().x();
  msg.position.y = pose.translation().y();
  msg.position.z = pose.translation().z();
  const Eigen::Quaterniond q(pose.rotation());
  msg.orientation.x = q.x();
  msg.orientation.y = q.y();
  msg.orientation.z = q.z();
  msg.orientation.w = q.w();
  return msg;
}

sensor_msgs::JointState toJointState(const sixdof_core::RobotState& state) {
  sensor_msgs::JointState msg;
  for (const auto& joint : state.model().joints()) {
    if (joint.type == sixdof_core::JointType::kFixed) continue;
    msg.name.push_back(joint.name);
    msg.position.push_back(state.jointPosition(joint.name));
  }
  return msg;
}

trajectory_msgs::JointTrajectory toJointTrajectory(const sixdof_core::Trajectory& trajectory) {
  trajectory_msgs::JointTrajectory msg;
  msg.joint_names = trajectory.joint_names;
  for (const auto& point : trajectory.points) {
    trajectory_msgs::JointTrajectoryPoint p;
    p.positions = point.positions;
    p.velocities = point.velocities;
    p.accelerations = point.accelerations;
    p.time_from_start = ros::Duration(point.time_from_start);
    msg.points.push_back(p);
  }
  return msg;
}

sixdof_core::Trajectory fromJointTrajectory(const trajectory_msgs::JointTrajectory& trajectory) {
  sixdof_core::Trajectory result;
  result.joint_names = trajectory.joint_names;
  for (const auto& p : trajectory.points) {
    sixdof_core::TrajectoryPoint point;
    point.positions = p.positions;
    point.velocities = p.velocities;
    point.accelerations = p.accelerations;
    point.time_from_start = p.time_from_start.toSec();
    result.points.push_back(point);
  }
  return result;
}

}  // namespace sixdof_planning
