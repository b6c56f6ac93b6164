#pragma once
// plan_kinematic_path (MoveIt's plan_service_capability): one MotionPlanRequest through MotionPlanner.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"
#include "sixdof_planning/motion_planner.h"

namespace sixdof_planning {

class MotionPlanService {  // plan_kinematic_path
 public:
  explicit MotionPlanService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetMotionPlanRequest& request, sixdof_msgs::GetMotionPlanResponse& response);

 private:
  MoveGroupContext* context_;
  MotionPlanner planner_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
