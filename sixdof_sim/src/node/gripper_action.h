#pragma once
// gripper_controller/gripper_cmd: a control_msgs/GripperCommand action server around a GripperController
// driving the finger joint (the other finger mimics it in the World).

#include <actionlib/server/action_server.h>
#include <ros/node_handle.h>
#include <control_msgs/GripperCommandAction.h>

#include <functional>
#include <optional>

#include "joint_driver.h"
#include "sixdof_sim/controllers.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

class GripperActionHandler : public JointDriver {
 public:
  using Server = actionlib::ActionServer<control_msgs::GripperCommandAction>;

  // nh: the controller's namespace (the action is nh/gripper_cmd). Throws std::invalid_argument if the
  // joint is unknown or a mimic joint.
  GripperActionHandler(ros::NodeHandle nh, GripperControllerConfig config, World& world, JointArbiter& arbiter,
                       std::function<double()> clock);

  void update(double now) override;
  void release() override;
  void reset() override;
  void publishFeedback(const ros::Time& stamp) override;

 private:
  void goalCallback(Server::GoalHandle gh);
  void cancelCallback(Server::GoalHandle gh);
  control_msgs::GripperCommandResult makeResult(bool reached_goal, bool stalled) const;
  void finishActive(bool succeeded, bool canceled, bool reached_goal, bool stalled, const std::string& text);

  GripperController controller_;
  World& world_;
  JointArbiter& arbiter_;
  std::function<double()> clock_;
  std::size_t index_;  // in the World's joints
  std::optional<Server::GoalHandle> active_;
  Server server_;
};

}  // namespace sixdof_sim
