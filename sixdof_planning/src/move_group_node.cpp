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
#include "sixdof_planning/planning_scene_topics_capability.h"
#include "sixdof_planning/query_robot_model_service_capability.h"
#include "sixdof_planning/retime_trajectory_service_capability.h"
#include "sixdof_planning/state_validation_service_capability.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

MoveGroupNode::MoveGroupNode(ros::NodeHandle nh, ros::NodeHandle private_nh) {
  context_ = std::make_unique<MoveGroupContext>(nh, loadConfig(nh, private_nh));
  executor_ = std::make_unique<TrajectoryExecutor>(context_.get());
  occupancy_map_ = std::make_unique<OccupancyMapMonitor>(context_.get());
  // Services and actions under MoveIt's names, relative to the node handle's namespace.
  fk_ = std::make_unique<ForwardKinematicsService>(context_.get(), "compute_fk");
  ik_ = std::make_unique<InverseKinematicsService>(context_.get(), "compute_ik");
  plan_ = std::make_unique<MotionPlanService>(context_.get(), "plan_kinematic_path");
  cartesian_ = std::make_unique<CartesianPathService>(context_.get(), "compute_cartesian_path");
  validity_ = std::make_unique<StateValidityService>(context_.get(), "check_state_validity");
  retime_ = std::make_unique<RetimeTrajectoryService>(context_.get(), "retime_trajectory");
  get_scene_ = std::make_unique<GetPlanningSceneService>(context_.get(), "get_planning_scene");
  apply_scene_ = std::make_unique<ApplyPlanningSceneService>(context_.get(), "apply_planning_scene");
  move_group_ = std::make_unique<MoveGroupActionCapability>(context_.get(), executor_.get(), "move_group");
  execute_trajectory_ = std::make_unique<ExecuteTrajectoryActionCapability>(context_.get(), executor_.get(),
                                                                            "execute_trajectory");
  robot_model_ = std::make_unique<QueryRobotModelService>(context_.get(), "get_robot_model");
  scene_topics_ = std::make_unique<PlanningSceneTopics>(context_.get());
}

template <class F>
void MoveGroupNode::forEachService(F f) {
  f(*fk_);
  f(*ik_);
  f(*plan_);
  f(*cartesian_);
  f(*validity_);
  f(*retime_);
  f(*get_scene_);
  f(*apply_scene_);
  f(*robot_model_);
}

void MoveGroupNode::start() {
  forEachService([](auto& service) { service.start(); });
}

MoveGroupNode::~MoveGroupNode() {
  forEachService([](auto& service) { service.stop(); });
}

}  // namespace sixdof_planning
