#pragma once
// get_robot_model: the robot model move_group plans with (groups, joint order, limits, named states, end
// effectors, mimic joints), so that Python clients ask instead of parsing URDF/SRDF by rules of their own
// (moveit_commander gets the same from MoveIt's C++ RobotModel in-process).

#include "sixdof_planning/move_group_capability.h"

namespace sixdof_core {
class RobotModel;
}  // namespace sixdof_core

namespace sixdof_planning {

// The model as a get_robot_model response (without the error code): exposed for tests.
void describeRobotModel(const sixdof_core::RobotModel& model, sixdof_msgs::GetRobotModelResponse* response);

class QueryRobotModelService : public ServiceCapability<QueryRobotModelService> {
 public:
  using ServiceCapability::ServiceCapability;
  bool handle(sixdof_msgs::GetRobotModelRequest& request, sixdof_msgs::GetRobotModelResponse& response);
};

}  // namespace sixdof_planning
