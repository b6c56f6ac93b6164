#pragma once
// The whole move_group node: the shared context, the trajectory executor and one object per capability
// (each in its own <name>_capability.h, MoveIt's default_capabilities layout).

#include <memory>

#include <ros/node_handle.h>

#include "sixdof_planning/config.h"  // ConfigError

namespace sixdof_planning {

class MoveGroupContext;
class TrajectoryExecutor;
class OccupancyMapMonitor;
class ForwardKinematicsService;
class InverseKinematicsService;
class MotionPlanService;
class CartesianPathService;
class StateValidityService;
class RetimeTrajectoryService;
class GetPlanningSceneService;
class ApplyPlanningSceneService;
class MoveGroupActionCapability;
class ExecuteTrajectoryActionCapability;
class QueryRobotModelService;
class PlanningSceneTopics;

class MoveGroupNode {
 public:
  // Throws ConfigError on bad parameters.
  MoveGroupNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Stops the services' threads before any capability goes.
  ~MoveGroupNode();

  // Starts each service's thread; goals and topics wait for the caller's spinner.
  void start();

 private:
  std::unique_ptr<MoveGroupContext> context_;
  std::unique_ptr<TrajectoryExecutor> executor_;
  std::unique_ptr<OccupancyMapMonitor> occupancy_map_;
  std::unique_ptr<ForwardKinematicsService> fk_;
  std::unique_ptr<InverseKinematicsService> ik_;
  std::unique_ptr<MotionPlanService> plan_;
  std::unique_ptr<CartesianPathService> cartesian_;
  std::unique_ptr<StateValidityService> validity_;
  std::unique_ptr<RetimeTrajectoryService> retime_;
  std::unique_ptr<GetPlanningSceneService> get_scene_;
  std::unique_ptr<ApplyPlanningSceneService> apply_scene_;
  std::unique_ptr<MoveGroupActionCapability> move_group_;
  std::unique_ptr<ExecuteTrajectoryActionCapability> execute_trajectory_;
  std::unique_ptr<QueryRobotModelService> robot_model_;
  std::unique_ptr<PlanningSceneTopics> scene_topics_;

  // Calls f on every service capability.
  template <class F>
  void forEachService(F f);
};

}  // namespace sixdof_planning
