#include "sixdof_planning/motion_planner.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <sixdof_core/primitive_dimensions.h>

#include <moveit_msgs/MotionPlanRequest.h>
#include <moveit_msgs/MotionPlanResponse.h>
#include <ros/console.h>

#include "sixdof_planning/constraints.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/stage_timer.h"
#include "sixdof_planning/tcpros_service_server.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {

ErrorCode goalError(const std::string& what, const std::string& message, const std::string& source) {
  return makeError(ErrorCode::INVALID_GOAL_CONSTRAINTS, what + ": " + message, source);
}

// The target of a position goal: the centre of its constraint region's one primitive (MoveGroupInterface sends a
// sphere of radius goal_position_tolerance around the target), in the constraint's frame; IK solves for the centre,
// which lies inside any region.
ErrorCode goalRegionCentre(const moveit_msgs::PositionConstraint& pc, const std::string& what,
                           const std::string& source, Eigen::Vector3d* centre) {
  const auto& region = pc.constraint_region;
  if (!region.meshes.empty() || region.primitives.size() != 1 || region.primitive_poses.size() != 1) {
    return goalError(what, "constraint_region must hold exactly one primitive (a sphere around the target), got " +
                               std::to_string(region.primitives.size()) + " primitives and " +
                               std::to_string(region.meshes.size()) + " meshes",
                     source);
  }
  const auto& primitive = region.primitives[0];
  const auto type = primitiveType(primitive.type);
  if (!type || primitive.dimensions.size() != sixdof_core::primitiveDimensionCount(*type)) {
    return goalError(what, "constraint_region.primitives[0] must be a BOX, SPHERE or CYLINDER with its dimensions",
                     source);
  }
  for (double d : primitive.dimensions) {
    if (!std::isfinite(d) || d < 0.0) {
      return goalError(what, "constraint_region.primitives[0] has a negative or non-finite dimension", source);
    }
  }
  for (double v : {pc.target_point_offset.x, pc.target_point_offset.y, pc.target_point_offset.z}) {
    if (!std::isfinite(v)) return goalError(what, "target_point_offset is not finite", source);
  }
  const ErrorCode code = validatePose(region.primitive_poses[0], what + ".constraint_region.primitive_poses[0]", source);
  if (!isSuccess(code)) return recode(code, ErrorCode::INVALID_GOAL_CONSTRAINTS);
  const auto& p = region.primitive_poses[0].position;
  *centre = Eigen::Vector3d(p.x, p.y, p.z);
  return makeSuccess(source);
}

}  // namespace

sixdof_core::CollisionReport checkStateCollision(const sixdof_core::RobotState& state,
                                                 const sixdof_core::CollisionScene& scene) {
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(scene.linkNames().size());
  for (const auto& link : scene.linkNames()) poses.push_back(state.linkTransform(link));
  // The boolean query first (a third of the report's cost): most states asked about are free.
  if (!scene.isColliding(poses)) return {};
  return scene.checkCollision(poses);
}

std::string boundsViolation(const sixdof_core::RobotState& state, double tolerance) {
  const auto& model = state.model();
  for (size_t i = 0; i < model.variableCount(); ++i) {
    const auto& joint = model.variableJoint(i);
    const double value = state.positions()[i];
    if (joint.limits.bounded && (value < joint.limits.lower - tolerance || value > joint.limits.upper + tolerance)) {
      return joint.name + " = " + formatNumber(value) + " is outside [" + formatNumber(joint.limits.lower) + ", " +
             formatNumber(joint.limits.upper) + "]";
    }
  }
  return "";
}

std::string fixStartStateBounds(double max_error, sixdof_core::RobotState* state) {
  const auto& model = state->model();
  Eigen::VectorXd positions = state->positions();
  std::string moved;
  for (size_t i = 0; i < model.variableCount(); ++i) {
    const auto& joint = model.variableJoint(i);
    if (!joint.limits.bounded) continue;
    const double value = positions[i];
    double bound = value;
    if (value < joint.limits.lower && joint.limits.lower - value <= max_error) bound = joint.limits.lower;
    if (value > joint.limits.upper && value - joint.limits.upper <= max_error) bound = joint.limits.upper;
    if (bound == value) continue;
    positions[i] = bound;
    moved += (moved.empty() ? "" : ", ") + joint.name + " " + formatNumber(value) + " -> " + formatNumber(bound);
  }
  if (!moved.empty()) state->setPositions(positions);
  return moved;
}

std::string describeContact(const sixdof_core::Contact& contact) {
  return "'" + contact.body1 + "' collides with '" + contact.body2 + "'";
}

ErrorCode planningStatusToError(const sixdof_core::PlanningResult& result, const std::string& source) {
  using S = sixdof_core::PlanningStatus;
  const std::string source_name = source + " (OMPL " + result.planner_id + ")";
  if (result.status == S::kSuccess) return makeSuccess(source_name);
  static const std::map<S, int> kCodes = {
      {S::kInvalidRequest, ErrorCode::FAILURE},         {S::kInvalidStart, ErrorCode::START_STATE_INVALID},
      {S::kInvalidGoal, ErrorCode::GOAL_STATE_INVALID}, {S::kGoalInCollision, ErrorCode::GOAL_IN_COLLISION},
      {S::kNoIkSolution, ErrorCode::NO_IK_SOLUTION},    {S::kTimeout, ErrorCode::TIMED_OUT},
  };
  const auto code = kCodes.find(result.status);
  return makeError(code != kCodes.end() ? code->second : ErrorCode::PLANNING_FAILED, result.message, source_name);
}

ErrorCode MotionPlanner::planToGoal(const sixdof_core::PlanningContext& planning, const sixdof_core::RobotState& start,
                                    const moveit_msgs::Constraints& goal, const std::string& what,
                                    const sixdof_core::PlanningOptions& options, const std::string& source,
                                    sixdof_core::PlanningResult* result) const {
  const auto& model = *context_->model();
  const std::string& group = planning.group();
  if (!goal.visibility_constraints.empty()) {
    return goalError(what, "visibility constraints are not supported as goals", source);
  }
  const bool has_joints = !goal.joint_constraints.empty();
  const bool has_pose = !goal.position_constraints.empty() || !goal.orientation_constraints.empty();
  if (has_joints && has_pose) {
    return goalError(what, "mixing joint constraints with position/orientation constraints is not supported", source);
  }
  if (!has_joints && !has_pose) return goalError(what, "has no constraints", source);
  if (has_joints) {
    const auto* joint_group = model.findGroup(group);
    const auto& active = joint_group->active_joints;
    Eigen::VectorXd target = start.groupPositions(group);
    Eigen::VectorXd tolerance = Eigen::VectorXd::Zero(target.size());
    std::vector<bool> seen(active.size(), false);
    for (size_t i = 0; i < goal.joint_constraints.size(); ++i) {
      const auto& c = goal.joint_constraints[i];
      const std::string cwhat = what + ".joint_constraints[" + std::to_string(i) + "]";
      if (model.jointIndex(c.joint_name) < 0) return goalError(cwhat, "unknown joint '" + c.joint_name + "'", source);
      const auto it = std::find(active.begin(), active.end(), c.joint_name);
      if (it == active.end()) {
        return goalError(cwhat, "joint '" + c.joint_name + "' is not an active joint of group '" + group +
                                    "' (its joints: " + joinNames(active) + ")",
                         source);
      }
      const size_t k = static_cast<size_t>(it - active.begin());
      if (seen[k]) return goalError(cwhat, "joint '" + c.joint_name + "' is constrained twice", source);
      seen[k] = true;
      if (!std::isfinite(c.position) || !std::isfinite(c.tolerance_above) || !std::isfinite(c.tolerance_below) ||
          c.tolerance_above < 0.0 || c.tolerance_below < 0.0) {
        return goalError(cwhat, "position must be finite and tolerances finite and >= 0 (joint '" + c.joint_name + "')",
                         source);
      }
      target[k] = c.position;
      // The core's goal region is symmetric: the smaller side keeps every accepted state inside the request's.
      tolerance[k] = std::min(c.tolerance_above, c.tolerance_below);
    }
    const std::string violation = planning.pathConstraintViolation(start, target);
    if (!violation.empty()) {
      return makeError(ErrorCode::GOAL_VIOLATES_PATH_CONSTRAINTS, what + ": " + violation, source);
    }
    auto problem = planning.problem(start, options);
    problem.joint_goal = sixdof_core::JointGoal{target, tolerance};
    *result = sixdof_core::plan(problem);
    return planningStatusToError(*result, source);
  }
  // Pose or position goal.
  if (goal.position_constraints.size() != 1 || goal.orientation_constraints.size() > 1) {
    return goalError(what,
                     "pose goals need exactly one position constraint and at most one orientation constraint "
                     "(orientation-only goals are not supported)",
                     source);
  }
  const auto& pc = goal.position_constraints[0];
  const std::string pwhat = what + ".position_constraints[0]";
  Eigen::Isometry3d link_in_tip;
  ErrorCode code = context_->linkInTip(group, pc.link_name, source, &link_in_tip);
  if (!isSuccess(code)) {
    code.message = pwhat + ": " + code.message;
    return code;
  }
  Eigen::Vector3d position;
  code = goalRegionCentre(pc, pwhat, source, &position);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d frame;
  code = SceneStore::frameTransform(start, pc.header.frame_id, source, &frame);
  if (!isSuccess(code)) return code;
  position = frame * position;
  const Eigen::Vector3d offset(pc.target_point_offset.x, pc.target_point_offset.y, pc.target_point_offset.z);
  const auto solver = context_->ikSolver(group);
  const Eigen::Isometry3d base_pose = start.linkTransform(solver->chain().baseLink());
  sixdof_core::PoseGoalOptions pose_options;
  pose_options.ik = context_->ikOptions(group);
  if (goal.orientation_constraints.empty()) {
    if (!offset.isZero() || !link_in_tip.translation().isZero()) {
      return goalError(pwhat, "a position-only goal needs the tip link itself (no target_point_offset, no offset link)",
                       source);
    }
    *result = planning.planToPosition(start, base_pose.inverse() * position, pose_options, options);
    return planningStatusToError(*result, source);
  }
  const auto& oc = goal.orientation_constraints[0];
  const std::string owhat = what + ".orientation_constraints[0]";
  if (oc.link_name != pc.link_name) {
    return goalError(owhat, "link '" + oc.link_name + "' differs from the position constraint's '" + pc.link_name + "'",
                     source);
  }
  geometry_msgs::Pose orientation_pose;
  orientation_pose.orientation = oc.orientation;
  code = validatePose(orientation_pose, owhat, source);
  if (!isSuccess(code)) return recode(code, ErrorCode::INVALID_GOAL_CONSTRAINTS);
  Eigen::Isometry3d oframe;
  code = SceneStore::frameTransform(start, oc.header.frame_id, source, &oframe);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d link_pose = Eigen::Isometry3d::Identity();
  link_pose.linear() = oframe.rotation() * poseToEigen(orientation_pose).rotation();
  link_pose.translation() = position - link_pose.rotation() * offset;
  const Eigen::Isometry3d tip_pose = link_pose * link_in_tip.inverse();
  *result = planning.planToPose(start, base_pose.inverse() * tip_pose, pose_options, options);
  return planningStatusToError(*result, source);
}

// MoveIt fields sixdof does not support, refused by name (FAILURE), and the workspace's consistency.
ErrorCode checkRequestFields(const moveit_msgs::MotionPlanRequest& request, const std::string& planning_frame,
                             const std::string& source) {
  const auto refuse = [&](const std::string& message) { return makeError(ErrorCode::FAILURE, message, source); };
  if (!request.pipeline_id.empty() && request.pipeline_id != "ompl") {
    return refuse("pipeline_id '" + request.pipeline_id + "' is not available (the only pipeline is 'ompl')");
  }
  if (!request.trajectory_constraints.constraints.empty()) {
    return refuse("trajectory_constraints are not supported");
  }
  if (!request.reference_trajectories.empty()) return refuse("reference_trajectories are not supported");
  if (!std::isfinite(request.max_cartesian_speed) || request.max_cartesian_speed < 0.0) {
    return refuse("max_cartesian_speed must be finite and >= 0, got " + formatNumber(request.max_cartesian_speed));
  }
  if (request.max_cartesian_speed > 0.0) {
    return refuse("max_cartesian_speed (" + formatNumber(request.max_cartesian_speed) +
                  " m/s) is not supported: limit the speed with max_velocity_scaling_factor");
  }
  // As in MoveIt, the workspace bounds only multi-DOF (planar, floating) joints, which sixdof models do not have:
  // it must make sense, it does not restrict an arm.
  const auto& workspace = request.workspace_parameters;
  const auto& lo = workspace.min_corner;
  const auto& hi = workspace.max_corner;
  for (double v : {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}) {
    if (!std::isfinite(v)) return refuse("workspace_parameters has a non-finite corner");
  }
  if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) {
    return refuse("workspace_parameters.min_corner is above max_corner on some axis");
  }
  const std::string& frame = workspace.header.frame_id;
  if (!frame.empty() && frame != planning_frame) {
    return makeError(ErrorCode::FRAME_TRANSFORM_FAILURE,
                     "workspace_parameters.header.frame_id '" + frame + "' is not the planning frame '" +
                         planning_frame + "'",
                     source);
  }
  return makeSuccess(source);
}

ErrorCode MotionPlanner::plan(const moveit_msgs::MotionPlanRequest& request, const std::string& source,
                              moveit_msgs::MotionPlanResponse* response,
                              std::shared_ptr<const SceneStore> base_scene) const {
  StageTimer timer;
  const ErrorCode code = planRequest(request, source, response, std::move(base_scene), &timer);
  if (isSuccess(code)) {
    timer.mark("cleanup");
    // Where a solved request's time goes until its answer (move_group_bench reads it with this logger at debug
    // level).
    TcprosServiceServer::afterAnswer(
        [timer] { ROS_DEBUG_STREAM_NAMED("timing", "plan stages (ms): " << timer.text()); });
  }
  return answer(code, response);
}

ErrorCode MotionPlanner::planRequest(const moveit_msgs::MotionPlanRequest& request, const std::string& source,
                                     moveit_msgs::MotionPlanResponse* response,
                                     std::shared_ptr<const SceneStore> base_scene, StageTimer* timer) const {
  const auto& model = *context_->model();
  const auto& config = context_->config();
  response->group_name = request.group_name;
  ErrorCode code = validateGroup(model, request.group_name, source);
  if (!isSuccess(code)) return code;
  code = checkRequestFields(request, context_->planningFrame(), source);
  if (!isSuccess(code)) return code;
  ScalingFactors scaling;
  code = validateScalingFactors(request.max_velocity_scaling_factor, request.max_acceleration_scaling_factor, "max_",
                                source, &scaling);
  if (!isSuccess(code)) return code;
  if (!std::isfinite(request.allowed_planning_time) || request.allowed_planning_time < 0.0) {
    return makeError(ErrorCode::FAILURE,
                     "allowed_planning_time must be >= 0 (0: the default), got " +
                         formatNumber(request.allowed_planning_time),
                     source);
  }
  // Each attempt holds a planner (and a thread when they run in parallel): an unbounded count ran out of memory.
  constexpr int kMaxPlanningAttempts = 1000;
  if (request.num_planning_attempts < 0 || request.num_planning_attempts > kMaxPlanningAttempts) {
    return makeError(ErrorCode::FAILURE,
                     "num_planning_attempts must be in [0, " + std::to_string(kMaxPlanningAttempts) + "] (0: 1), got " +
                         std::to_string(request.num_planning_attempts),
                     source);
  }
  if (request.goal_constraints.empty()) {
    return makeError(ErrorCode::INVALID_GOAL_CONSTRAINTS, "goal_constraints is empty", source);
  }
  sixdof_core::PathConstraints path_constraints;
  code = toPathConstraints(model, request.group_name, request.path_constraints, "path_constraints", source,
                           &path_constraints);
  if (!isSuccess(code)) return code;
  sixdof_core::RobotState start(context_->model());
  std::shared_ptr<const SceneStore> scene;
  code = context_->resolveRobotState(request.start_state, "start_state", source, &start, &scene, base_scene);
  if (!isSuccess(code)) return code;
  const std::string moved = fixStartStateBounds(config.start_state_max_bounds_error, &start);
  if (!moved.empty()) ROS_INFO_STREAM("start state moved onto its joint limits: " << moved);
  response->trajectory_start.joint_state = toJointState(start);
  const std::string out_of_bounds = boundsViolation(start);
  if (!out_of_bounds.empty()) {
    return makeError(ErrorCode::START_STATE_INVALID, "start state: " + out_of_bounds, source);
  }
  const auto report = checkStateCollision(start, *scene->collision());
  if (report.colliding) {
    return makeError(ErrorCode::START_STATE_IN_COLLISION,
                     "start state in collision: " + describeContact(report.contacts.front()), source);
  }
  sixdof_core::PlanningOptions options;
  options.planner_id = request.planner_id.empty() ? config.default_planner_id : request.planner_id;
  options.allowed_planning_time =
      request.allowed_planning_time > 0.0 ? request.allowed_planning_time : config.default_planning_time;
  options.num_planning_attempts = std::max(1, request.num_planning_attempts);
  options.longest_valid_segment_fraction = config.longest_valid_segment_fraction;
  options.simplify = config.simplify_solutions;
  timer->mark("checks and start state");
  std::unique_ptr<sixdof_core::PlanningContext> planning;
  try {
    planning = std::make_unique<sixdof_core::PlanningContext>(
        context_->model(), scene->collision(), request.group_name, context_->ikSolver(request.group_name));
    planning->setPathConstraints(path_constraints);
  } catch (const std::exception& e) {
    return makeError(ErrorCode::FAILURE, std::string("path_constraints: ") + e.what(), source);
  }
  const std::string violation = planning->pathConstraintViolation(start, start.groupPositions(request.group_name));
  if (!violation.empty()) return makeError(ErrorCode::START_STATE_VIOLATES_PATH_CONSTRAINTS, violation, source);
  timer->mark("planning context");
  sixdof_core::PlanningResult result;
  for (size_t i = 0; i < request.goal_constraints.size(); ++i) {
    code = planToGoal(*planning, start, request.goal_constraints[i], "goal_constraints[" + std::to_string(i) + "]",
                      options, source, &result);
    if (isSuccess(code)) break;
  }
  response->planning_time = result.planning_time;
  if (!isSuccess(code)) return code;
  timer->mark("planning");
  timer->add("reported planning", 1e3 * result.planning_time);
  sixdof_core::Trajectory trajectory;
  const auto& joints = model.findGroup(request.group_name)->active_joints;
  code = context_->timeParameterize(joints, result.path, scaling.velocity, scaling.acceleration, source, &trajectory,
                                    config.trajectory_sample_period);
  if (!isSuccess(code)) return code;
  timer->mark("time parameterization");
  response->trajectory.joint_trajectory = toJointTrajectory(trajectory);
  response->trajectory.joint_trajectory.header.frame_id = context_->planningFrame();
  timer->mark("trajectory message");
  const double duration = trajectory.duration();
  // The display trajectory, and freeing the planning context, wait for the answer to be written.
  std::shared_ptr<sixdof_core::PlanningContext> used(std::move(planning));
  TcprosServiceServer::afterAnswer(
      [context = context_, start = std::move(start), trajectory = std::move(trajectory),
       used = std::move(used)]() mutable {
        context->publishDisplayTrajectory(start, std::move(trajectory));
        used.reset();
      });
  timer->mark("deferring display");
  return makeSuccess(code.source, "planned " + std::to_string(result.path.size()) + " waypoints in " +
                                      formatNumber(result.planning_time) + " s, trajectory " +
                                      formatNumber(duration) + " s");
}

}  // namespace sixdof_planning
