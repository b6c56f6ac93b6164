#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <actionlib/client/simple_action_client.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <control_msgs/FollowJointTrajectoryAction.h>

#include "sixdof_planning/errors.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

// MoveIt's TrajectoryExecutionManager with the simple controller manager: a trajectory is split among the
// FollowJointTrajectory controllers of controller_list, sent to all of them at once and watched until every
// controller reports, the allowed duration (expected x scaling + margin) passes, a controller stops reporting
// (action server lost, /clock or joint_states silent: the watchdog, on the wall clock) or the caller preempts.
class TrajectoryExecutor {
 public:
  explicit TrajectoryExecutor(MoveGroupContext* context);

  // Blocks until the execution ends. `preempt_requested` is polled; when it returns true the controllers'
  // goals are cancelled and PREEMPTED is returned. One execution at a time: a second caller waits.
  ErrorCode execute(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source,
                    const std::function<bool()>& preempt_requested);

 private:
  using Client = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;

  ErrorCode validate(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source) const;
  // One goal per controller that has joints in the trajectory (plus mimic joints of trajectory joints).
  ErrorCode split(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source,
                  std::map<std::string, trajectory_msgs::JointTrajectory>* parts) const;
  // After the controllers reported success: waits (up to 1 s of wall time) until joint_states show every joint of the
  // trajectory within start_state_tolerance of its last point, as MoveIt's waitForRobotToStop waits for the robot to
  // settle. The next request's current state is then the motion's end even when this node's /clock lags behind the
  // simulator's (a simulator many times faster than real time under load: joint_states stamped after the request's
  // ROS time can predate the motion's end). A warning on timeout; the execution still succeeded.
  void waitForEnd(const trajectory_msgs::JointTrajectory& trajectory, const std::string& source) const;
  void cancelAll(const std::map<std::string, trajectory_msgs::JointTrajectory>& parts);
  std::string serverName(const std::string& controller) const;
  // Waits up to kServerWaitSeconds of wall-clock time for the controller's action server.
  bool waitForServer(const std::string& controller);
  // Why the controllers stopped reporting (an action server lost, /clock or joint_states silent for longer than
  // `limit` wall-clock seconds), or empty while they are alive.
  std::string controllerSilence(const std::map<std::string, trajectory_msgs::JointTrajectory>& parts,
                                double limit) const;

  MoveGroupContext* context_;
  std::map<std::string, std::unique_ptr<Client>> clients_;  // by controller name
  std::map<std::string, std::string> action_names_;        // by controller name
  std::mutex execution_mutex_;
};

}  // namespace sixdof_planning
