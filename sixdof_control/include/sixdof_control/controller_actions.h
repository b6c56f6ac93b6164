#pragma once
// The controllers' ROS interface, one implementation for the simulator's node and the driver node (each hosts the
// controllers on its joints: controller_host.h), as joint_trajectory_controller and gripper_action_controller have
// it:
// - <controller>/follow_joint_trajectory (control_msgs/FollowJointTrajectory): goals rejected with the
//   controller's error_code and error_string, ended with them; a new goal preempts the active one, a gripper_cmd
//   goal the trajectory goal that commands the same joint (and the other way round);
// - <controller>/state (control_msgs/JointTrajectoryControllerState: desired, actual, error = desired - actual) at
//   state_publish_rate while the controller commands its joints;
// - <controller>/query_state (control_msgs/QueryTrajectoryState): the commanded trajectory at a time; the call fails
//   (reason logged) when the controller does not command its joints or has nothing commanded;
// - <controller>/gripper_cmd (control_msgs/GripperCommand) on the gripper controller.

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/GripperCommandAction.h>
#include <control_msgs/QueryTrajectoryState.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/service_server.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sixdof_control/controller_host.h"
#include "sixdof_control/controller_params.h"

namespace sixdof_control {

sixdof_core::TrajectoryGoal fromMsg(const control_msgs::FollowJointTrajectoryGoal& msg);

// An accepted goal's handle until the host reports its end. The end can come before the goal callback has accepted
// the handle (the host runs on another thread): it is then kept and applied right after the acceptance.
template <class Handle, class Outcome>
struct ActionGoal {
  explicit ActionGoal(Handle h) : handle(std::move(h)) {}
  Handle handle;
  bool accepted = false;
  std::optional<Outcome> early_end;
};

// The goal an action server runs, at most one at a time: from its acceptance until the host reports its end.
// Thread-safe.
template <class Handle, class Outcome>
class ActiveGoal {
 public:
  using Goal = ActionGoal<Handle, Outcome>;

  // Marks the goal accepted and makes it the active one, unless it already ended (then calls finish(that end)).
  template <class Finish>
  void accept(const std::shared_ptr<Goal>& goal, Finish finish) {
    goal->handle.setAccepted();
    std::optional<Outcome> early;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      goal->accepted = true;
      early = goal->early_end;
      if (!early) active_ = goal;
    }
    if (early) finish(*early);
  }

  // The host reported the goal's end: true when it is to be finished now, false when the end is kept for accept()
  // (the goal is not accepted yet).
  bool endNow(const std::shared_ptr<Goal>& goal, const Outcome& outcome) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!goal->accepted) {
      goal->early_end = outcome;
      return false;
    }
    if (active_ == goal) active_.reset();
    return true;
  }

  // The active goal, or null.
  std::shared_ptr<Goal> get() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return active_;
  }

  // True when `handle` is the active goal's.
  bool is(const Handle& handle) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return active_ && active_->handle == handle;
  }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<Goal> active_;
};

class TrajectoryActionServer {
 public:
  using Server = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;

  // nh: the controller's namespace. The host must outlive the server.
  TrajectoryActionServer(ros::NodeHandle nh, const TrajectoryControllerSetup& setup, ControllerHost& host);
  TrajectoryActionServer(const TrajectoryActionServer&) = delete;
  TrajectoryActionServer& operator=(const TrajectoryActionServer&) = delete;

  // The active goal's feedback, and the state topic when due (state_publish_rate of `stamp`'s clock); call at the
  // node's publishing rate.
  void publish(const ros::Time& stamp);

 private:
  using Goal = ActionGoal<Server::GoalHandle, GoalOutcome>;
  void goalCallback(Server::GoalHandle gh);
  void finish(Goal& goal, const GoalOutcome& outcome);
  bool queryState(control_msgs::QueryTrajectoryState::Request& request,
                  control_msgs::QueryTrajectoryState::Response& response);

  std::string name_;
  ControllerJoints joints_;
  ControllerHost& host_;
  double state_period_ = 0.0;  // s; 0 = no state topic
  double next_state_ = 0.0;    // stamp's clock
  ActiveGoal<Server::GoalHandle, GoalOutcome> active_;
  ros::Publisher state_pub_;
  ros::ServiceServer query_state_;
  Server server_;
};

class GripperActionServer {
 public:
  using Server = actionlib::ActionServer<control_msgs::GripperCommandAction>;

  // nh: the controller's namespace (the action is nh/gripper_cmd). The host must outlive the server.
  GripperActionServer(ros::NodeHandle nh, const std::string& gripper, ControllerHost& host);
  GripperActionServer(const GripperActionServer&) = delete;
  GripperActionServer& operator=(const GripperActionServer&) = delete;

  // The active goal's feedback (position, effort).
  void publish();

 private:
  using Goal = ActionGoal<Server::GoalHandle, GripperOutcome>;
  void goalCallback(Server::GoalHandle gh);
  void finish(Goal& goal, const GripperOutcome& outcome);
  control_msgs::GripperCommandResult makeResult(bool reached_goal, bool stalled) const;

  std::string name_;
  ControllerHost& host_;
  ActiveGoal<Server::GoalHandle, GripperOutcome> active_;
  Server server_;
};

// Every controller of the setup on ROS: a TrajectoryActionServer each (in nh/<name>), and the gripper's
// GripperActionServer.
class ControllerActions {
 public:
  ControllerActions(const ros::NodeHandle& nh, const ControllerSetup& setup, ControllerHost& host);
  void publish(const ros::Time& stamp);

 private:
  std::vector<std::unique_ptr<TrajectoryActionServer>> trajectory_;
  std::unique_ptr<GripperActionServer> gripper_;
};

}  // namespace sixdof_control
