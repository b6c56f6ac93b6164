#pragma once
// get_planning_scene (MoveIt's get_planning_scene_service_capability): the whole current scene.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class GetPlanningSceneService {  // get_planning_scene
 public:
  explicit GetPlanningSceneService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPlanningSceneRequest& request, sixdof_msgs::GetPlanningSceneResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
