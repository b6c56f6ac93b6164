#include "sixdof_planning/conversions.h"

#include <tf2_eigen/tf2_eigen.h>

namespace sixdof_planning {

Eigen::Isometry3d poseToEigen(const geometry_msgs::Pose& pose) {
  // tf2_eigen converts the quaternion as it is; normalising first keeps the rotation orthonormal.
  Eigen::Quaterniond q;
  tf2::fromMsg(pose.orientation, q);
  geometry_msgs::Pose unit = pose;
  unit.orientation = tf2::toMsg(q.normalized());
  Eigen::Isometry3d result;
  tf2::fromMsg(unit, result);
  return result;
}

geometry_msgs::Pose eigenToPose(const Eigen::Isometry3d& pose) { return tf2::toMsg(pose); }

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
