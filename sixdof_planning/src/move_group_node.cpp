#include "sixdof_planning/move_group_node.h"

#include "sixdof_planning/apply_planning_scene_service_capability.h"
#include "sixdof_planning/cartesian_path_service_capability.h"
#include "sixdof_planning/execute_trajectory_action_capability.h"
#include "sixdof_planning/get_planning_scene_service_capability.h"
#include "sixdof_planning/kinematics_service_capability.h"
#include "sixdof_planning/move_action_capability.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/occupancy_map_monitor.h"
#include "sixdof_planning/plan_service_capability.h"
#include "sixdof_planning/query_robot_model_service_capability.h"
#include "sixdof_planning/retime_trajectory_service_capability.h"
#include "sixdof_planning/state_validation_service_capability.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

MoveGroupNode::MoveGroupNode(ros::NodeHandle nh, ros::NodeHandle private_nh) {
  context_ = std::make_unique<MoveGroupContext>(nh, loadConfig(nh, private_nh));
  executor_ = std::make_unique<TrajectoryExecutor>(context_.get());
  occupancy_map_ = std::make_unique<OccupancyMapMonitor>(context_.get());
  fk_ = std::make_unique<ForwardKinematicsService>(context_.get());
  ik_ = std::make_unique<InverseKinematicsService>(context_.get());
  plan_ = std::make_unique<MotionPlanService>(context_.get());
  cartesian_ = std::make_unique<CartesianPathService>(context_.get());
  validity_ = std::make_unique<StateValidityService>(context_.get());
  retime_ = std::make_unique<RetimeTrajectoryService>(context_.get());
  get_scene_ = std::make_unique<GetPlanningSceneService>(context_.get());
  apply_scene_ = std::make_unique<ApplyPlanningSceneService>(context_.get());
  move_group_ = std::make_unique<MoveGroupActionCapability>(context_.get(), executor_.get());
  execute_trajectory_ = std::make_unique<ExecuteTrajectoryActionCapability>(context_.get(), executor_.get());
  robot_model_ = std::make_unique<QueryRobotModelService>(context_.get());
}

MoveGroupNode::~MoveGroupNode() = default;

}  // namespace sixdof_planning
