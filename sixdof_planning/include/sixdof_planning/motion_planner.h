#pragma once

#include <memory>
#include <string>
#include <vector>

#include <sixdof_core/collision.h>
#include <sixdof_core/planning.h>
#include <sixdof_core/planning_context.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_planning/errors.h"
#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

// Collision report of a full robot state in a scene (every colliding pair, one contact each).
sixdof_core::CollisionReport checkStateCollision(const sixdof_core::RobotState& state,
                                                 const sixdof_core::CollisionScene& scene);
// "joint2 = 2.5 is outside [-1.92, 1.92]" for the first active joint further than `tolerance` out of its limits,
// else "".
std::string boundsViolation(const sixdof_core::RobotState& state, double tolerance = 0.0);

// Moves every bounded joint that is at most `max_error` outside its limits onto the limit; returns a description
// of what was moved ("finger1_joint -2e-08 -> 0"), or "" when nothing was. Joints further out are left as they are
// for boundsViolation to report.
std::string fixStartStateBounds(double max_error, sixdof_core::RobotState* state);
// "link3 collides with box" for the first contact of a report.
std::string describeContact(const sixdof_core::Contact& contact);

// MoveIt's planning pipeline for one MotionPlanRequest: request checks, start state, path constraints (joint
// and position constraints), goal (joint constraints, or a pose or position constraint of the tip or a link fixed
// to it), OMPL through sixdof_core, time parameterization. Shared by plan_kinematic_path and the move_group action.
class MotionPlanner {
 public:
  explicit MotionPlanner(MoveGroupContext* context) : context_(context) {}

  // Fills the whole response, error_code included, and returns the outcome with its words. base_scene: the scene
  // to plan in (null: the current one).
  ErrorCode plan(const moveit_msgs::MotionPlanRequest& request, const std::string& source,
                 moveit_msgs::MotionPlanResponse* response,
                 std::shared_ptr<const SceneStore> base_scene = nullptr) const;

 private:
  // planRequest marks the end of each stage on `timer`.
  ErrorCode planRequest(const moveit_msgs::MotionPlanRequest& request, const std::string& source,
                        moveit_msgs::MotionPlanResponse* response, std::shared_ptr<const SceneStore> base_scene,
                        StageTimer* timer) const;
  // Plans to one goal alternative.
  ErrorCode planToGoal(const sixdof_core::PlanningContext& planning, const sixdof_core::RobotState& start,
                       const moveit_msgs::Constraints& goal, const std::string& what,
                       const sixdof_core::PlanningOptions& options, const std::string& source,
                       sixdof_core::PlanningResult* result) const;

  MoveGroupContext* context_;
};

ErrorCode planningStatusToError(const sixdof_core::PlanningResult& result, const std::string& source);

}  // namespace sixdof_planning
