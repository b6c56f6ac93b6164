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
// A point's positions, velocities and accelerations, which the message and the core name alike, appended to `to`;
// the time is converted by the caller.
template <class From, class To>
To& appendMotion(const From& from, std::vector<To>* to) {
  To& point = to->emplace_back();
  point.positions = from.positions;
  point.velocities = from.velocities;
  point.accelerations = from.accelerations;
  return point;
}
}  // namespace

trajectory_msgs::JointTrajectory toJointTrajectory(const sixdof_core::Trajectory& trajectory) {
  trajectory_msgs::JointTrajectory msg;
  msg.joint_names = trajectory.joint_names;
  msg.points.reserve(trajectory.points.size());
  for (const auto& point : trajectory.points) {
    appendMotion(point, &msg.points).time_from_start = ros::Duration(point.time_from_start);
  }
  return msg;
}

sixdof_core::Trajectory fromJointTrajectory(const trajectory_msgs::JointTrajectory& trajectory) {
  sixdof_core::Trajectory result;
  result.joint_names = trajectory.joint_names;
  result.points.reserve(trajectory.points.size());
  for (const auto& p : trajectory.points) appendMotion(p, &result.points).time_from_start = p.time_from_start.toSec();
  return result;
}

}  // namespace sixdof_planning
