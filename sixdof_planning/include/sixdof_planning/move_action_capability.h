#pragma once
// The move_group action (MoveIt's move_action_capability): plan a MotionPlanRequest and, unless plan_only,
// execute it, with the goal's planning_scene_diff applied to a copy of the scene for this goal only.

#include <boost/shared_ptr.hpp>

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_planning {

class MoveGroupActionCapability : public ActionCapability<MoveGroupActionCapability, moveit_msgs::MoveGroupAction> {
 public:
  using ActionCapability::ActionCapability;
  void execute(const boost::shared_ptr<const moveit_msgs::MoveGroupGoal>& goal);

 private:
  // Plans (and executes) the goal, filling the result but its error code; returns the outcome.
  ErrorCode run(const moveit_msgs::MoveGroupGoal& goal, moveit_msgs::MoveGroupResult* result);
};

}  // namespace sixdof_planning
