#pragma once
// apply_planning_scene (MoveIt's apply_planning_scene_service_capability): a scene diff, all or nothing.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class ApplyPlanningSceneService {  // apply_planning_scene
 public:
  explicit ApplyPlanningSceneService(MoveGroupContext* context);
  bool handle(sixdof_msgs::ApplyPlanningSceneRequest& request, sixdof_msgs::ApplyPlanningSceneResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
