#include "sixdof_planning/conversions.h"

#include <shape_msgs/SolidPrimitive.h>
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

std::optional<sixdof_core::ShapeType> primitiveType(uint8_t msg_type) {
  using P = shape_msgs::SolidPrimitive;
  if (msg_type == P::BOX) return sixdof_core::ShapeType::kBox;
  if (msg_type == P::SPHERE) return sixdof_core::ShapeType::kSphere;
  if (msg_type == P::CYLINDER) return sixdof_core::ShapeType::kCylinder;
  return std::nullopt;
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

namespace {
// A point's positions, velocities and accelerations, which the message and the core name alike; the time is
// converted by the caller.
template <class From, class To>
To copyMotion(const From& from) {
  To to;
  to.positions = from.positions;
  to.velocities = from.velocities;
  to.accelerations = from.accelerations;
  return to;
}
}  // namespace

trajectory_msgs::JointTrajectory toJointTrajectory(const sixdof_core::Trajectory& trajectory) {
  trajectory_msgs::JointTrajectory msg;
  msg.joint_names = trajectory.joint_names;
  for (const auto& point : trajectory.points) {
    msg.points.push_back(copyMotion<sixdof_core::TrajectoryPoint, trajectory_msgs::JointTrajectoryPoint>(point));
    msg.points.back().time_from_start = ros::Duration(point.time_from_start);
  }
  return msg;
}

sixdof_core::Trajectory fromJointTrajectory(const trajectory_msgs::JointTrajectory& trajectory) {
  sixdof_core::Trajectory result;
  result.joint_names = trajectory.joint_names;
  for (const auto& p : trajectory.points) {
    result.points.push_back(copyMotion<trajectory_msgs::JointTrajectoryPoint, sixdof_core::TrajectoryPoint>(p));
    result.points.back().time_from_start = p.time_from_start.toSec();
  }
  return result;
}

}  // namespace sixdof_planning
