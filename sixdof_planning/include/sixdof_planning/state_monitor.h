#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/spinner.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>

#include <sixdof_core/robot_model.h>

namespace sixdof_planning {

// How alive the robot's state sources are, in wall-clock seconds (infinity: never heard of).
struct StateLiveness {
  double joint_states_age;  // since the last joint_states message
  double clock_still;       // since /clock last advanced (0 when the node does not use simulated time)
};

// The robot's current joint positions from joint_states (MoveIt's CurrentStateMonitor). Several
// publishers may each cover part of the joints; the latest value per joint wins.
// joint_states and /clock are received on a callback queue and thread of their own: how fresh they are must not
// depend on whether the node's spinner threads are busy planning or executing.
class CurrentStateMonitor {
 public:
  CurrentStateMonitor(ros::NodeHandle& nh, sixdof_core::RobotModelConstPtr model, const std::string& topic);
  ~CurrentStateMonitor();

  // The current state once every active joint has been heard of, waiting up to `timeout` seconds for the
  // missing ones. False (and *missing lists them) when some joint was never received; the joints that were
  // received are set on *state all the same. The state may be old: see liveness().
  bool currentState(double timeout, sixdof_core::RobotState* state, std::vector<std::string>* missing) const;

  // Waits (wall clock, at most timeout s) until a joint_states message stamped at or after `time` has been applied,
  // as MoveIt's waitForCurrentState does before planning from the current state: under load the subscriber may still
  // be working through older messages. False on timeout, and at once when the publisher does not stamp its messages.
  bool waitForStateNewerThan(const ros::Time& time, double timeout) const;

  // Waits (wall clock, at most timeout s) until `reached` holds for the latest positions of the active joints (by
  // name; a joint never received is absent). False on timeout.
  bool waitForPositions(const std::function<bool(const std::map<std::string, double>&)>& reached,
                        double timeout) const;

  StateLiveness liveness() const;

  // Applies a message; exposed so tests and callers can feed states directly.
  void update(const sensor_msgs::JointState& msg);

 private:
  using Clock = std::chrono::steady_clock;
  std::vector<std::string> missingJoints() const;  // with mutex_ held
  void clockUpdate(const rosgraph_msgs::Clock& msg);

  sixdof_core::RobotModelConstPtr model_;
  ros::CallbackQueue queue_;
  ros::Subscriber subscriber_, clock_subscriber_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::map<std::string, double> positions_;  // active joints only
  bool received_ = false;
  Clock::time_point last_update_;
  ros::Time last_stamp_;  // of the last joint_states message with our joints
  bool clock_received_ = false;
  ros::Time last_clock_;
  Clock::time_point last_clock_advance_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace sixdof_planning
