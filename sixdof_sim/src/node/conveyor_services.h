#pragma once
// sixdof_sim/set_conveyor (sixdof_msgs/SetConveyor), sixdof_sim/conveyor_states (sixdof_msgs/ConveyorStates), the
// sinks' deletions in the log, and the suction cup's vacuum on <controller>/gripper_cmd (control_msgs/GripperCommand:
// command.position > 0 on, <= 0 off; the goal succeeds after the next physics step with result.position 1 or 0,
// result.stalled true when the cup holds an object, reached_goal true).

#include <actionlib/server/action_server.h>
#include <control_msgs/GripperCommandAction.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/service_server.h>
#include <sixdof_msgs/SetConveyor.h>

#include <memory>
#include <optional>
#include <string>

#include "sixdof_sim/world.h"

namespace sixdof_sim {

class ConveyorServices {
 public:
  // sim_nh: the simulator's namespace (sixdof_sim); nh: the controllers' namespace (the gripper_cmd action, served
  // only when the world has a suction cup).
  ConveyorServices(ros::NodeHandle sim_nh, ros::NodeHandle nh, World& world);
  // After every physics step: ends a vacuum goal, logs the sinks' deletions and an object the cup refuses.
  void afterStep();
  void publish(const ros::Time& stamp);

 private:
  using Server = actionlib::ActionServer<control_msgs::GripperCommandAction>;
  bool setConveyor(sixdof_msgs::SetConveyor::Request& req, sixdof_msgs::SetConveyor::Response& res);
  void vacuumGoal(Server::GoalHandle goal);
  void vacuumCancel(Server::GoalHandle goal);
  control_msgs::GripperCommandResult vacuumResult() const;

  World& world_;
  ros::ServiceServer set_conveyor_;
  ros::Publisher states_pub_;
  std::unique_ptr<Server> vacuum_server_;
  std::optional<Server::GoalHandle> vacuum_goal_;
  std::string refused_;  // the object the cup last refused, logged once
};

}  // namespace sixdof_sim
