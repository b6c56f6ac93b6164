#pragma once

#include <memory>

#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>

#include <sixdof_msgs/ApplyPlanningScene.h>
#include <sixdof_msgs/ExecuteTrajectoryAction.h>
#include <sixdof_msgs/GetCartesianPath.h>
#include <sixdof_msgs/GetMotionPlan.h>
#include <sixdof_msgs/GetPlanningScene.h>
#include <sixdof_msgs/GetPositionFK.h>
#include <sixdof_msgs/GetPositionIK.h>
#include <sixdof_msgs/GetStateValidity.h>
#include <sixdof_msgs/MoveGroupAction.h>

#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"
#include "sixdof_planning/trajectory_execution.h"

namespace sixdof_planning {

// One class per service/action (MoveIt's move_group capabilities). Each advertises its interface in the
// context's namespace on construction and answers every request with an error code naming the problem.

class ForwardKinematicsService {  // compute_fk
 public:
  explicit ForwardKinematicsService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPositionFK::Request& request, sixdof_msgs::GetPositionFK::Response& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class InverseKinematicsService {  // compute_ik
 public:
  explicit InverseKinematicsService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPositionIK::Request& request, sixdof_msgs::GetPositionIK::Response& response);

 private:
  ErrorCode solve(const sixdof_msgs::PositionIKRequest& request, sixdof_msgs::RobotState* solution) const;

  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class MotionPlanService {  // plan_kinematic_path
 public:
  explicit MotionPlanService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetMotionPlan::Request& request, sixdof_msgs::GetMotionPlan::Response& response);

 private:
  MoveGroupContext* context_;
  MotionPlanner planner_;
  ros::ServiceServer server_;
};

class CartesianPathService {  // compute_cartesian_path
 public:
  explicit CartesianPathService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetCartesianPath::Request& request, sixdof_msgs::GetCartesianPath::Response& response);

 private:
  ErrorCode compute(const sixdof_msgs::GetCartesianPath::Request& request,
                    sixdof_msgs::GetCartesianPath::Response* response) const;

  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class StateValidityService {  // check_state_validity
 public:
  explicit StateValidityService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetStateValidity::Request& request, sixdof_msgs::GetStateValidity::Response& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class GetPlanningSceneService {  // get_planning_scene
 public:
  explicit GetPlanningSceneService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetPlanningScene::Request& request, sixdof_msgs::GetPlanningScene::Response& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class ApplyPlanningSceneService {  // apply_planning_scene
 public:
  explicit ApplyPlanningSceneService(MoveGroupContext* context);
  bool handle(sixdof_msgs::ApplyPlanningScene::Request& request, sixdof_msgs::ApplyPlanningScene::Response& response);

 private:
  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

class MoveGroupActionCapability {  // action move_group: plan, and unless plan_only, execute
 public:
  MoveGroupActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor);

 private:
  void execute(const sixdof_msgs::MoveGroupGoalConstPtr& goal);

  MoveGroupContext* context_;
  TrajectoryExecutor* executor_;
  MotionPlanner planner_;
  actionlib::SimpleActionServer<sixdof_msgs::MoveGroupAction> server_;
};

class ExecuteTrajectoryActionCapability {  // action execute_trajectory
 public:
  ExecuteTrajectoryActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor);

 private:
  void execute(const sixdof_msgs::ExecuteTrajectoryGoalConstPtr& goal);

  MoveGroupContext* context_;
  TrajectoryExecutor* executor_;
  actionlib::SimpleActionServer<sixdof_msgs::ExecuteTrajectoryAction> server_;
};

// The whole node: context, executor and every capability.
class MoveGroupNode {
 public:
  // Throws ConfigError on bad parameters.
  MoveGroupNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  std::unique_ptr<MoveGroupContext> context_;
  std::unique_ptr<TrajectoryExecutor> executor_;
  std::unique_ptr<ForwardKinematicsService> fk_;
  std::unique_ptr<InverseKinematicsService> ik_;
  std::unique_ptr<MotionPlanService> plan_;
  std::unique_ptr<CartesianPathService> cartesian_;
  std::unique_ptr<StateValidityService> validity_;
  std::unique_ptr<GetPlanningSceneService> get_scene_;
  std::unique_ptr<ApplyPlanningSceneService> apply_scene_;
  std::unique_ptr<MoveGroupActionCapability> move_group_;
  std::unique_ptr<ExecuteTrajectoryActionCapability> execute_trajectory_;
};

}  // namespace sixdof_planning
