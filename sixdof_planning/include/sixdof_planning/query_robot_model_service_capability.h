#pragma once
// get_robot_model: the robot model move_group plans with (groups, joint order, limits, named states, end
// effectors, mimic joints), so that Python clients ask instead of parsing URDF/SRDF by rules of their own
// (moveit_commander gets the same from MoveIt's C++ RobotModel in-process).

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_msgs {
template <class ContainerAllocator>
struct GetRobotModelRequest_;
template <class ContainerAllocator>
struct GetRobotModelResponse_;
typedef GetRobotModelRequest_<std::allocator<void>> GetRobotModelRequest;
typedef GetRobotModelResponse_<std::allocator<void>> GetRobotModelResponse;
}  // namespace sixdof_msgs

namespace sixdof_core {
class RobotModel;
}  // namespace sixdof_core

namespace sixdof_planning {

// The model as a get_robot_model response (without the error code): exposed for tests.
void describeRobotModel(const sixdof_core::RobotModel& model, sixdof_msgs::GetRobotModelResponse* response);

class QueryRobotModelService {  // get_robot_model
 public:
  explicit QueryRobotModelService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetRobotModelRequest& request, sixdof_msgs::GetRobotModelResponse& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
