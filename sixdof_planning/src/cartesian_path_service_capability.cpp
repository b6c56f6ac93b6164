#include "sixdof_planning/cartesian_path_service_capability.h"

#include <cmath>
#include <sstream>

#include <sixdof_core/cartesian_path.h>
#include <sixdof_core/planning_context.h>
#include <ros/console.h>
#include <moveit_msgs/GetCartesianPath.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/constraints.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {
const char* const kCartesianSource = "compute_cartesian_path";

ErrorCode nonNegative(double value, const std::string& what) {
  if (!std::isfinite(value) || value < 0.0) {
    std::ostringstream out;
    out << what << " must be finite and >= 0, got " << value;
    return makeError(ErrorCode::FAILURE, out.str(), kCartesianSource);
  }
  return makeSuccess(kCartesianSource);
}

// The whole request; the response gets everything but the error code.
ErrorCode computePath(MoveGroupContext* context, const moveit_msgs::GetCartesianPathRequest& request,
                      moveit_msgs::GetCartesianPathResponse* response) {
  const auto& model = *context->model();
  ErrorCode code = validateGroup(model, request.group_name, kCartesianSource);
  if (!isSuccess(code)) return code;
  if (request.waypoints.empty()) return makeError(ErrorCode::FAILURE, "waypoints is empty", kCartesianSource);
  for (size_t i = 0; i < request.waypoints.size(); ++i) {
    code = validatePose(request.waypoints[i], "waypoints[" + std::to_string(i) + "]", kCartesianSource);
    if (!isSuccess(code)) return code;
  }
  if (!std::isfinite(request.max_step) || request.max_step <= 0.0) {
    std::ostringstream out;
    out << "max_step must be > 0, got " << request.max_step;
    return makeError(ErrorCode::FAILURE, out.str(), kCartesianSource);
  }
  for (const auto& check : {nonNegative(request.jump_threshold, "jump_threshold"),
                            nonNegative(request.prismatic_jump_threshold, "prismatic_jump_threshold"),
                            nonNegative(request.revolute_jump_threshold, "revolute_jump_threshold")}) {
    if (!isSuccess(check)) return check;
  }
  code = nonNegative(request.max_cartesian_speed, "max_cartesian_speed");
  if (!isSuccess(code)) return code;
  if (request.max_cartesian_speed > 0.0) {
    return makeError(ErrorCode::FAILURE,
                     "max_cartesian_speed is not supported: retime the path (retime_trajectory) to slow it down",
                     kCartesianSource);
  }
  sixdof_core::PathConstraints path_constraints;
  code = toPathConstraints(model, request.group_name, request.path_constraints, "path_constraints", kCartesianSource,
                           &path_constraints);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d link_in_tip;
  code = context->linkInTip(request.group_name, request.link_name, kCartesianSource, &link_in_tip);
  if (!isSuccess(code)) return code;

  sixdof_core::RobotState start(context->model());
  std::shared_ptr<const SceneStore> scene;
  code = context->resolveRobotState(request.start_state, "start_state", kCartesianSource, &start, &scene);
  if (!isSuccess(code)) return code;
  // As for planning (MoveIt's FixStartStateBounds): a measured state a hair past a limit (a joint held at +pi
  // reading 3.14161) is moved onto it; the path's first point would otherwise be refused by the controller.
  const std::string moved = fixStartStateBounds(context->config().start_state_max_bounds_error, &start);
  if (!moved.empty()) ROS_INFO_STREAM("Cartesian path: start state moved onto its joint limits: " << moved);
  response->start_state.joint_state = toJointState(start);
  Eigen::Isometry3d frame;
  code = SceneStore::frameTransform(start, request.header.frame_id, kCartesianSource, &frame);
  if (!isSuccess(code)) return code;
  const auto solver = context->ikSolver(request.group_name);
  const Eigen::Isometry3d base = start.linkTransform(solver->chain().baseLink());
  std::vector<Eigen::Isometry3d> waypoints;
  for (const auto& pose : request.waypoints) {
    waypoints.push_back(base.inverse() * frame * poseToEigen(pose) * link_in_tip.inverse());
  }
  sixdof_core::JumpThreshold jump;
  jump.relative = request.jump_threshold;
  jump.prismatic = request.prismatic_jump_threshold;
  jump.revolute = request.revolute_jump_threshold;

  std::unique_ptr<sixdof_core::PlanningContext> planning;
  try {
    planning = std::make_unique<sixdof_core::PlanningContext>(context->model(), scene->collision(),
                                                              request.group_name, solver);
    planning->setPathConstraints(path_constraints);
  } catch (const std::exception& e) {
    return makeError(ErrorCode::FAILURE, std::string("path_constraints: ") + e.what(), kCartesianSource);
  }
  const std::string violation = planning->pathConstraintViolation(start, start.groupPositions(request.group_name));
  if (!violation.empty()) {
    return makeError(ErrorCode::START_STATE_VIOLATES_PATH_CONSTRAINTS, violation, kCartesianSource);
  }
  // The tip moves by at most max_step between points, so a link fixed to it does as well when the
  // rotation is small; MoveIt interpolates the requested link the same way.
  const auto result = planning->cartesianPath(start, waypoints, request.max_step, jump, request.avoid_collisions,
                                              context->ikOptions(request.group_name));
  using S = sixdof_core::CartesianStatus;
  if (result.status == S::kInvalidRequest) {
    return makeError(ErrorCode::FAILURE, result.message, kCartesianSource);
  }
  if (result.status == S::kInvalidStart) {
    return makeError(ErrorCode::START_STATE_IN_COLLISION, result.message, kCartesianSource);
  }
  if (result.path.empty()) {
    return makeError(ErrorCode::FAILURE, "Cartesian path without a start point: " + result.message, kCartesianSource);
  }
  response->fraction = result.fraction;
  const auto& joints = model.findGroup(request.group_name)->active_joints;
  sixdof_core::Trajectory trajectory;
  if (result.path.size() >= 2) {
    // As MoveIt's service: timed at full speed; clients retime to their scaling factors.
    code = context->timeParameterize(joints, result.path, 1.0, 1.0, kCartesianSource, &trajectory);
    if (!isSuccess(code)) return code;
  } else {
    // Nothing achieved: the path is the start state alone.
    trajectory.joint_names = joints;
    sixdof_core::TrajectoryPoint point;
    point.positions.assign(result.path.front().data(), result.path.front().data() + result.path.front().size());
    trajectory.points.push_back(point);
  }
  response->solution.joint_trajectory = toJointTrajectory(trajectory);
  response->solution.joint_trajectory.header.frame_id = context->planningFrame();
  if (trajectory.points.size() > 1) context->publishDisplayTrajectory(start, std::move(trajectory));
  // As in MoveIt, a partial path is a successful call; the fraction and message say how far it got.
  std::ostringstream message;
  message << "fraction " << result.fraction;
  if (result.status != S::kSuccess) message << ": " << sixdof_core::toString(result.status) << ": " << result.message;
  return makeSuccess(kCartesianSource, message.str());
}
}  // namespace

ErrorCode CartesianPathService::handle(const moveit_msgs::GetCartesianPathRequest& request,
                                  moveit_msgs::GetCartesianPathResponse& response) {
  response.fraction = 0.0;
  return answer(computePath(context_, request, &response), &response);
}

template class ServiceCapability<CartesianPathService>;

}  // namespace sixdof_planning
