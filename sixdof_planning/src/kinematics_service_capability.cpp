#include "sixdof_planning/kinematics_service_capability.h"

#include <algorithm>
#include <chrono>
#include <random>

#include <sixdof_core/ik_analytic.h>

#include <moveit_msgs/GetPositionFK.h>
#include <moveit_msgs/GetPositionIK.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/constraints.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {
const char* const kIkSource = "compute_ik";

ErrorCode solveIk(MoveGroupContext* context, const moveit_msgs::PositionIKRequest& request,
                  moveit_msgs::RobotState* solution) {
  const auto& model = *context->model();
  ErrorCode code = validateGroup(model, request.group_name, kIkSource);
  if (!isSuccess(code)) return code;
  const auto solver = context->ikSolver(request.group_name);
  if (!solver) {
    return makeError(ErrorCode::NO_IK_SOLUTION,
                     "group '" + request.group_name + "' has no IK solver (no entry in robot_description_kinematics)",
                     kIkSource);
  }
  if (!constraintsEmpty(request.constraints)) {
    return makeError(ErrorCode::FAILURE, "ik_request.constraints are not supported", kIkSource);
  }
  if (!request.ik_link_names.empty() || !request.pose_stamped_vector.empty()) {
    return makeError(ErrorCode::FAILURE,
                     "ik_request.ik_link_names / pose_stamped_vector (several tip links) are not supported: give one "
                     "ik_link_name and pose_stamped",
                     kIkSource);
  }
  code = validatePose(request.pose_stamped.pose, "ik_request.pose_stamped.pose", kIkSource);
  if (!isSuccess(code)) return code;
  if (request.timeout.toSec() < 0.0) {
    return makeError(ErrorCode::FAILURE, "ik_request.timeout is negative", kIkSource);
  }
  sixdof_core::RobotState state(context->model());
  std::shared_ptr<const SceneStore> scene;
  code = context->resolveRobotState(request.robot_state, "ik_request.robot_state", kIkSource, &state, &scene);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d frame;
  code = SceneStore::frameTransform(state, request.pose_stamped.header.frame_id, kIkSource, &frame);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d link_in_tip;
  code = context->linkInTip(request.group_name, request.ik_link_name, kIkSource, &link_in_tip);
  if (!isSuccess(code)) return code;
  const Eigen::Isometry3d base = state.linkTransform(solver->chain().baseLink());
  const Eigen::Isometry3d target =
      base.inverse() * frame * poseToEigen(request.pose_stamped.pose) * link_in_tip.inverse();

  sixdof_core::IkOptions options = context->ikOptions(request.group_name);
  if (request.timeout.toSec() > 0.0) options.timeout = request.timeout.toSec();
  options.seed = state.groupPositions(request.group_name);

  // A candidate is acceptable when it is within limits and, if asked, collision-free in the scene.
  std::string rejection;
  auto acceptable = [&](const Eigen::VectorXd& q) {
    sixdof_core::RobotState candidate = state;
    candidate.setGroupPositions(request.group_name, q);
    if (!request.avoid_collisions) return true;
    const auto report = checkStateCollision(candidate, *scene->collision());
    if (report.colliding) rejection = describeContact(report.contacts.front());
    return !report.colliding;
  };
  Eigen::VectorXd found;
  bool ok = false;
  std::string failure;
  if (const auto* analytic = dynamic_cast<const sixdof_core::AnalyticIkSolver*>(solver.get())) {
    // Every closed-form branch, nearest the seed first.
    auto all = analytic->solveAll(target, options.seed);
    std::sort(all.solutions.begin(), all.solutions.end(), [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return (a - options.seed).norm() < (b - options.seed).norm();
    });
    for (const auto& q : all.solutions) {
      if (acceptable(q)) {
        found = q;
        ok = true;
        break;
      }
    }
    failure = all.solutions.empty() ? all.message
                                    : std::to_string(all.solutions.size()) + " IK solutions, all in collision (" +
                                          rejection + ")";
  } else {
    // Iterative solvers: restart from random seeds until a collision-free solution or the time budget is spent.
    std::mt19937_64 rng(options.random_seed);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options.timeout);
    const double budget = options.timeout;
    int collisions = 0;
    do {
      const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
      options.timeout = std::max(left, 1e-4);
      options.random_seed = rng();
      const auto result = solver->solve(target, options);
      if (!result.ok()) {
        failure = result.message;
        if (collisions == 0) break;  // the solver spent the budget without any solution
        continue;
      }
      if (acceptable(result.solution)) {
        found = result.solution;
        ok = true;
        break;
      }
      ++collisions;
      failure = std::to_string(collisions) + " IK solutions found within " + std::to_string(budget) +
                " s, all in collision (" + rejection + ")";
      // Next start: a random configuration, to reach another branch.
      const auto& chain = solver->chain();
      const Eigen::VectorXd lower = chain.lowerLimits();
      const Eigen::VectorXd upper = chain.upperLimits();
      for (Eigen::Index i = 0; i < options.seed.size(); ++i) {
        options.seed[i] = std::uniform_real_distribution<double>(lower[i], upper[i])(rng);
      }
    } while (std::chrono::steady_clock::now() < deadline);
  }
  const std::string source = kIkSource + std::string(" (") + solver->name() + ")";
  if (!ok) return makeError(ErrorCode::NO_IK_SOLUTION, "no IK solution: " + failure, source);
  state.setGroupPositions(request.group_name, found);
  solution->joint_state = toJointState(state);
  return makeSuccess(source);
}
}  // namespace

ErrorCode ForwardKinematicsService::handle(const moveit_msgs::GetPositionFKRequest& request,
                                           moveit_msgs::GetPositionFKResponse& response) {
  return answer(fk(request, &response), &response);
}

ErrorCode ForwardKinematicsService::fk(const moveit_msgs::GetPositionFKRequest& request,
                                       moveit_msgs::GetPositionFKResponse* response) const {
  const auto& model = *context_->model();
  for (const auto& link : request.fk_link_names) {
    const ErrorCode code = validateLink(model, link, service_);
    if (!isSuccess(code)) return code;
  }
  sixdof_core::RobotState state(context_->model());
  std::shared_ptr<const SceneStore> scene;
  ErrorCode code = context_->resolveRobotState(request.robot_state, "robot_state", service_, &state, &scene);
  if (!isSuccess(code)) return code;
  Eigen::Isometry3d frame;
  code = SceneStore::frameTransform(state, request.header.frame_id, service_, &frame);
  if (!isSuccess(code)) return code;
  const std::string frame_id = request.header.frame_id.empty() ? context_->planningFrame() : request.header.frame_id;
  for (const auto& link : request.fk_link_names) {
    geometry_msgs::PoseStamped pose;
    pose.header.frame_id = frame_id;
    pose.header.stamp = ros::Time::now();
    pose.pose = eigenToPose(frame.inverse() * state.linkTransform(link));
    response->pose_stamped.push_back(pose);
    response->fk_link_names.push_back(link);
  }
  return makeSuccess(service_);
}

ErrorCode InverseKinematicsService::handle(const moveit_msgs::GetPositionIKRequest& request,
                                           moveit_msgs::GetPositionIKResponse& response) {
  return answer(solveIk(context_, request.ik_request, &response.solution), &response);
}

template class ServiceCapability<ForwardKinematicsService>;
template class ServiceCapability<InverseKinematicsService>;

}  // namespace sixdof_planning
