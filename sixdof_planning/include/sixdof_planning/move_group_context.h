#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <sixdof_core/ik_solver.h>
#include <sixdof_core/robot_model.h>
#include <sixdof_core/time_parameterization.h>
#include <sixdof_core/trajectory.h>
#include <moveit_msgs/DisplayTrajectory.h>
#include <moveit_msgs/PlanningScene.h>
#include <moveit_msgs/RobotState.h>

#include "sixdof_planning/config.h"
#include "sixdof_planning/errors.h"
#include "sixdof_planning/scene_store.h"
#include "sixdof_planning/state_monitor.h"

namespace sixdof_planning {

// What every capability shares (MoveIt's MoveGroupContext): the robot model, IK solvers, the planning
// scene, the current state and the output topics. Thread-safe: capabilities run on an AsyncSpinner.
class MoveGroupContext {
 public:
  // Builds the model from the configuration; throws ConfigError naming what is wrong.
  MoveGroupContext(ros::NodeHandle nh, MoveGroupConfig config);

  const MoveGroupConfig& config() const { return config_; }
  const sixdof_core::RobotModelConstPtr& model() const { return model_; }
  const std::string& planningFrame() const { return model_->rootLink(); }
  ros::NodeHandle& nodeHandle() { return nh_; }

  // The group's IK solver (null for groups without kinematics configuration) and its configured options
  // (time budget = kinematics_solver_timeout x kinematics_solver_attempts, as MoveIt calls the solver
  // `attempts` times).
  std::shared_ptr<const sixdof_core::IkSolver> ikSolver(const std::string& group) const;
  sixdof_core::IkOptions ikOptions(const std::string& group) const;

  // The current state from joint_states (waits up to joint_state_timeout for missing joints). When joint_states
  // have been silent for longer than joint_state_timeout (the simulator or driver is gone) this is the last known
  // state, as in MoveIt, with a warning naming its age: planning keeps answering; execution refuses (see
  // TrajectoryExecutor).
  ErrorCode currentState(const std::string& source, sixdof_core::RobotState* state) const;
  // joint_states as received: how long (wall clock) joint_states and /clock have been silent, and waits for them.
  const CurrentStateMonitor& stateMonitor() const { return *state_monitor_; }
  // A request's robot state: its joints on top of the current state (the current state is only needed for
  // joints the message leaves out), and `base_scene` (null: the current scene) with the message's attached
  // objects: added to the scene's with is_diff, instead of the scene's without. `what` names the field; a
  // malformed state is INVALID_ROBOT_STATE.
  ErrorCode resolveRobotState(const moveit_msgs::RobotState& msg, const std::string& what, const std::string& source,
                              sixdof_core::RobotState* state, std::shared_ptr<const SceneStore>* scene,
                              std::shared_ptr<const SceneStore> base_scene = nullptr) const;

  std::shared_ptr<const SceneStore> scene() const;
  // Applies a scene message to the persistent scene (all or nothing) and publishes the markers and the monitored
  // scene.
  ErrorCode applyScene(const moveit_msgs::PlanningScene& msg, const std::string& source);
  // The scene as get_planning_scene answers it: the parts moveit_msgs/PlanningSceneComponents' bits ask for.
  moveit_msgs::PlanningScene sceneMessage(uint32_t components, const std::string& source) const;

  // Publishes a failed request's words on move_group/error_reports (sixdof_msgs/ErrorReport) and logs them:
  // moveit_msgs' responses carry at most the code. `caller` is the requesting node, `interface` the resolved
  // service or topic name.
  void reportError(const std::string& caller, const std::string& interface, const ErrorCode& code);

  // Swaps in a scene whose collision checks include `map` (a snapshot nobody changes), placed by map_pose.
  void setOccupancyMap(std::shared_ptr<const sixdof_core::OccupancyMap> map, const Eigen::Isometry3d& map_pose);

  // The pose of `link` in the frame of the group's IK tip link, for a link rigidly fixed to the tip (the tip
  // itself, or e.g. a tcp link); INVALID_LINK_NAME otherwise. An empty link means the tip.
  ErrorCode linkInTip(const std::string& group, const std::string& link, const std::string& source,
                      Eigen::Isometry3d* link_in_tip) const;

  // Time-optimal parameterization of a joint path under the configured limits and the scaling factors, sampled
  // every sample_period s (plans: ~trajectory_sample_period; Cartesian paths and retime_trajectory keep the core's
  // dense default, several points per Cartesian step, so that the straight line is followed between them).
  ErrorCode timeParameterize(const std::vector<std::string>& joints, const std::vector<Eigen::VectorXd>& path,
                             double velocity_scaling, double acceleration_scaling, const std::string& source,
                             sixdof_core::Trajectory* trajectory,
                             double sample_period = sixdof_core::TimeParameterizationOptions().sample_period) const;

  // The trajectory (with the planning frame) on move_group/display_planned_path. A subscriber that connects later
  // gets the last one, as from a latched topic; the message is built only when someone listens, so a plan nobody
  // watches costs no copy of its trajectory.
  void publishDisplayTrajectory(const sixdof_core::RobotState& start, sixdof_core::Trajectory trajectory);
  // The scene's markers and the whole scene on move_group/monitored_planning_scene, after each change.
  void publishScene();

 private:
  void warnIfStale(const std::string& source) const;
  // Sends the last display trajectory (built now if it was not) to a subscriber that has just connected.
  void sendLastDisplayTrajectory(const ros::SingleSubscriberPublisher& subscriber);
  void waitForCurrentState() const;

  ros::NodeHandle nh_;
  MoveGroupConfig config_;
  sixdof_core::RobotModelConstPtr model_;
  std::map<std::string, std::shared_ptr<const sixdof_core::IkSolver>> ik_solvers_;
  std::unique_ptr<CurrentStateMonitor> state_monitor_;

  mutable std::mutex scene_mutex_;
  std::shared_ptr<const SceneStore> scene_;

  std::mutex display_mutex_;
  // The last display trajectory: its message once built, else what it is built from.
  moveit_msgs::DisplayTrajectoryConstPtr display_msg_;
  std::unique_ptr<sixdof_core::RobotState> display_start_;
  sixdof_core::Trajectory display_trajectory_;
  ros::Publisher display_path_pub_;
  ros::Publisher markers_pub_;
  ros::Publisher monitored_scene_pub_;
  ros::Publisher error_reports_pub_;
};

}  // namespace sixdof_planning
