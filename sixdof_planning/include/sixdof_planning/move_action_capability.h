#pragma once
// The move_group action (MoveIt's move_action_capability): plan a MotionPlanRequest and, unless plan_only,
// execute it, with the goal's planning_scene_diff applied to a copy of the scene for this goal only.

#include <memory>

#include <boost/shared_ptr.hpp>

#include "sixdof_planning/fwd.h"
#include "sixdof_planning/motion_planner.h"

namespace sixdof_planning {

class MoveGroupActionCapability {  // action move_group: plan, and unless plan_only, execute
 public:
  MoveGroupActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor);
  ~MoveGroupActionCapability();

 private:
  void execute(const boost::shared_ptr<const sixdof_msgs::MoveGroupGoal>& goal);

  MoveGroupContext* context_;
  TrajectoryExecutor* executor_;
  MotionPlanner planner_;
  std::unique_ptr<actionlib::SimpleActionServer<sixdof_msgs::MoveGroupAction>> server_;
};

}  // namespace sixdof_planning
