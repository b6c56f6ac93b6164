#pragma once
// arm_controller/follow_joint_trajectory and gripper_controller/follow_joint_trajectory: a
// control_msgs/FollowJointTrajectory action server around a TrajectoryController driving World joints, the
// controller's state topic (<controller>/state, control_msgs/JointTrajectoryControllerState) and its
// query_state service (control_msgs/QueryTrajectoryState), as joint_trajectory_controller has them.

#include <actionlib/server/action_server.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/service_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/QueryTrajectoryState.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "joint_driver.h"
#include "sixdof_sim/controllers.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

class TrajectoryActionHandler : public JointDriver {
 public:
  using Server = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;

  // nh: the controller's namespace (the action is nh/follow_joint_trajectory). Mimic joints of the config
  // are checked against their master in every goal and left to the World to drive. Throws
  // std::invalid_argument when a mimic joint's master is not part of the controller.
  // state_publish_rate: Hz of nh/state (0 = not advertised); published from publishFeedback(), so at most at
  // the rate the node calls it (its publish_rate).
  TrajectoryActionHandler(ros::NodeHandle nh, TrajectoryControllerConfig config, World& world,
                          JointArbiter& arbiter, std::function<double()> clock, double state_publish_rate = 50.0);

  void update(double now) override;
  void release() override;
  void reset() override;
  void publishFeedback(const ros::Time& stamp) override;

 private:
  struct Mimic {
    std::size_t joint;   // index in the controller
    std::size_t master;  // index in the controller
    double multiplier;
    double offset;
  };

  void goalCallback(Server::GoalHandle gh);
  bool queryState(control_msgs::QueryTrajectoryState::Request& request,
                  control_msgs::QueryTrajectoryState::Response& response);
  void cancelCallback(Server::GoalHandle gh);
  std::string checkMimics(const TrajectoryGoal& goal) const;
  void readState(std::vector<double>* q, std::vector<double>* v) const;
  void finishActive(int code, const std::string& message, bool succeeded, bool canceled);
  bool ownsAny() const;

  TrajectoryController controller_;
  World& world_;
  JointArbiter& arbiter_;
  std::function<double()> clock_;
  std::vector<int> world_index_;        // per controller joint
  std::vector<std::string> commanded_;  // non-mimic joints: the World drives the mimics
  std::vector<Mimic> mimics_;
  std::optional<Server::GoalHandle> active_;
  TrajectoryUpdate last_update_;
  double state_period_ = 0.0;  // s; 0 = no state topic
  double next_state_ = 0.0;    // node clock
  ros::Publisher state_pub_;
  ros::ServiceServer query_state_;
  Server server_;
};

}  // namespace sixdof_sim
