#pragma once

#include <map>
#include <mutex>
#include <string>
#include <vector>
#include <condition_variable>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <sixdof_core/robot_model.h>

namespace sixdof_planning {

// The robot's current joint positions from joint_states (MoveIt's CurrentStateMonitor). Several
// publishers may each cover part of the joints; the latest value per joint wins.
class CurrentStateMonitor {
 public:
  CurrentStateMonitor(ros::NodeHandle& nh, sixdof_core::RobotModelConstPtr model, const std::string& topic);

  // The current state once every active joint has been heard of, waiting up to `timeout` seconds for the
  // missing ones. False (and *missing lists them) when some joint was never received; the joints that were
  // received are set on *state all the same.
  bool currentState(double timeout, sixdof_core::RobotState* state, std::vector<std::string>* missing) const;
  // Time of the latest joint_states message (zero before the first).
  ros::Time lastUpdate() const;

  // Applies a message; exposed so tests and callers can feed states directly.
  void update(const sensor_msgs::JointState& msg);

 private:
  std::vector<std::string> missingJoints() const;  // with mutex_ held

  sixdof_core::RobotModelConstPtr model_;
  ros::Subscriber subscriber_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::map<std::string, double> positions_;  // active joints only
  ros::Time last_update_;
};

}  // namespace sixdof_planning
