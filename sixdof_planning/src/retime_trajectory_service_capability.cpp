#include "sixdof_planning/retime_trajectory_service_capability.h"

#include <cmath>

#include <sixdof_core/trajectory.h>
#include <sixdof_msgs/RetimeTrajectory.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {
const char* const kRetimeSource = "retime_trajectory";

// Known, active, distinct joints and one finite position per joint at every point (INVALID_MOTION_PLAN); the
// times are not checked: they are what gets replaced.
ErrorCode validatePath(const sixdof_core::RobotModel& model, const trajectory_msgs::JointTrajectory& trajectory) {
  if (trajectory.joint_names.empty() || trajectory.points.empty()) {
    return makeError(ErrorCode::INVALID_MOTION_PLAN, "trajectory has no joints or no points", kRetimeSource);
  }
  ErrorCode code = validateTrajectoryJoints(model, trajectory.joint_names, kRetimeSource);
  if (!isSuccess(code)) return code;
  for (size_t i = 0; i < trajectory.points.size(); ++i) {
    const auto& positions = trajectory.points[i].positions;
    if (positions.size() != trajectory.joint_names.size()) {
      return makeError(ErrorCode::INVALID_MOTION_PLAN,
                       "point " + std::to_string(i) + " has " + std::to_string(positions.size()) + " positions for " +
                           std::to_string(trajectory.joint_names.size()) + " joints",
                       kRetimeSource);
    }
    for (size_t j = 0; j < positions.size(); ++j) {
      if (!std::isfinite(positions[j])) {
        return makeError(ErrorCode::INVALID_MOTION_PLAN,
                         "point " + std::to_string(i) + " has a non-finite position for joint '" +
                             trajectory.joint_names[j] + "'",
                         kRetimeSource);
      }
    }
  }
  return makeSuccess(kRetimeSource);
}
}  // namespace

ErrorCode RetimeTrajectoryService::handle(const sixdof_msgs::RetimeTrajectoryRequest& request,
                                          sixdof_msgs::RetimeTrajectoryResponse& response) {
  const ErrorCode code = answer(retime(request, &response), &response);
  response.error_message = isSuccess(code) ? "" : code.message;
  return code;
}

ErrorCode RetimeTrajectoryService::retime(const sixdof_msgs::RetimeTrajectoryRequest& request,
                                          sixdof_msgs::RetimeTrajectoryResponse* response) const {
  if (!request.trajectory.multi_dof_joint_trajectory.joint_names.empty()) {
    return makeError(ErrorCode::INVALID_MOTION_PLAN,
                     "trajectory.multi_dof_joint_trajectory is not supported (the robot model has no multi-DOF joints)",
                     kRetimeSource);
  }
  const auto& path = request.trajectory.joint_trajectory;
  ErrorCode code = validatePath(*context_->model(), path);
  if (!isSuccess(code)) return code;
  ScalingFactors scaling;
  code = validateScalingFactors(request.velocity_scaling_factor, request.acceleration_scaling_factor, "", kRetimeSource,
                                &scaling);
  if (!isSuccess(code)) return code;
  std::vector<Eigen::VectorXd> waypoints;
  for (const auto& point : path.points) {
    waypoints.push_back(Eigen::Map<const Eigen::VectorXd>(point.positions.data(), point.positions.size()));
  }
  sixdof_core::Trajectory trajectory;
  code = context_->timeParameterize(path.joint_names, waypoints, scaling.velocity, scaling.acceleration, kRetimeSource,
                                    &trajectory);
  if (!isSuccess(code)) return code;
  response->trajectory.joint_trajectory = toJointTrajectory(trajectory);
  response->trajectory.joint_trajectory.header = path.header;
  return makeSuccess(kRetimeSource, "retimed " + std::to_string(path.points.size()) + " points to " +
                                        formatNumber(trajectory.duration()) + " s");
}

template class ServiceCapability<RetimeTrajectoryService>;

}  // namespace sixdof_planning
