#pragma once
// get_robot_model: the robot model move_group plans with (groups, joint order, limits, named states, end
// effectors, mimic joints, the gripper's grasping information and, on request, the links' collision shapes), so that
// Python clients ask instead of parsing URDF/SRDF by rules of their own (moveit_commander gets the same from
// MoveIt's C++ RobotModel in-process).

#include <string>
#include <vector>

#include <sixdof_msgs/RobotModelGripper.h>
#include <sixdof_msgs/RobotModelLinkGeometry.h>

#include "sixdof_planning/grasping_config.h"
#include "sixdof_planning/move_group_capability.h"

namespace sixdof_core {
class RobotModel;
}  // namespace sixdof_core

namespace sixdof_planning {

// The model as a get_robot_model response (without the error code): exposed for tests.
void describeRobotModel(const sixdof_core::RobotModel& model, sixdof_msgs::GetRobotModelResponse* response);
// The grasping information move_group read from robot_description_grasping, as the response's grippers entry.
sixdof_msgs::RobotModelGripper describeGripper(const GraspingConfig& grasping);
// Every link's collision shapes (links with none are left out), meshes read by sixdof_core's loader with the URDF
// scale applied: the response's link_geometries. Returns "" on success, else a message naming the link and mesh
// file that cannot be read (then `geometries` is left as it was).
std::string describeCollisionGeometry(const sixdof_core::RobotModel& model,
                                      std::vector<sixdof_msgs::RobotModelLinkGeometry>* geometries);

class QueryRobotModelService : public ServiceCapability<QueryRobotModelService> {
 public:
  using ServiceCapability::ServiceCapability;
  ErrorCode handle(const sixdof_msgs::GetRobotModelRequest& request, sixdof_msgs::GetRobotModelResponse& response);
};

}  // namespace sixdof_planning
