#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include <sixdof_core/robot_model.h>

#include "sixdof_planning/grasping_config.h"

namespace sixdof_planning {

// Thrown on missing or malformed parameters; the message names the parameter and what is wrong.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// robot_description_kinematics/<group>/... (kinematics.yaml).
struct GroupKinematicsConfig {
  std::string solver;               // kinematics_solver: analytic | kdl | numeric
  double search_resolution = 0.005;  // kinematics_solver_search_resolution
  double timeout = 0.005;            // kinematics_solver_timeout, s
  int attempts = 3;                  // kinematics_solver_attempts
  bool position_only = false;        // position_only_ik
};

// robot_description_planning/joint_limits/<joint>/... (joint_limits.yaml), overriding the URDF.
struct JointLimitConfig {
  double max_velocity = 0.0;
  double max_acceleration = 0.0;
};

// One entry of controller_list (moveit_simple_controller_manager's format).
struct ControllerConfig {
  std::string name;       // e.g. arm_controller
  std::string action_ns;  // e.g. follow_joint_trajectory
  std::string type;       // FollowJointTrajectory
  std::vector<std::string> joints;

  std::string actionName() const { return action_ns.empty() ? name : name + "/" + action_ns; }
};

// One entry of ~sensors (MoveIt's sensors_3d.yaml); only occupancy_map_monitor/PointCloudOctomapUpdater.
struct OctomapSensorConfig {
  std::string sensor_plugin;
  std::string point_cloud_topic;
  double max_range = 5.0;         // m; the monitor's ~max_range unless the entry sets it
  int point_subsample = 1;        // use every n-th point
  double padding_offset = 0.03;   // m the self filter grows the robot's and known objects' shapes by
  double padding_scale = 1.0;     // and scales them by (before the offset)
  double max_update_rate = 0.0;   // Hz; 0: every cloud
  std::string filtered_cloud_topic;  // the cloud without masked points, in the sensor frame; empty: none
};

// The occupancy map monitor (MoveIt's occupancy_map_monitor parameters, private to move_group).
struct OccupancyMapConfig {
  std::string octomap_frame;        // ~octomap_frame; empty: the planning frame
  double octomap_resolution = 0.1;  // ~octomap_resolution, m
  double max_range = 5.0;           // ~max_range, m
  std::vector<OctomapSensorConfig> sensors;  // ~sensors; none: the map stays empty
};

struct MoveGroupConfig {
  std::string urdf;
  std::string srdf;
  // robot_description_grasping: a config package's grasping.yaml text (empty: the parameter is not set), and what
  // checkConfig reads from it (get_robot_model serves it).
  std::string grasping_yaml;
  std::optional<GraspingConfig> grasping;
  std::map<std::string, GroupKinematicsConfig> kinematics;  // by group
  std::map<std::string, JointLimitConfig> joint_limits;     // by active joint, every one filled
  std::vector<ControllerConfig> controllers;
  // robot_description_planning/default_robot_padding (MoveIt's name): m every robot link grows by in the
  // planning scene (collision checks of planning, IK, Cartesian paths and check_state_validity), >= 0.
  double default_robot_padding = 0.0;
  // Private parameters of the node.
  double default_planning_time = 5.0;     // ~default_planning_time, s
  std::string default_planner_id = "RRTConnect";  // ~default_planner_id
  double execution_duration_scaling = 1.2;  // ~allowed_execution_duration_scaling
  double execution_goal_margin = 0.5;       // ~allowed_goal_duration_margin, s
  double start_state_tolerance = 0.01;      // ~allowed_start_tolerance, rad or m
  // ~execution_watchdog_timeout: wall-clock seconds an execution tolerates /clock standing still or joint_states
  // staying silent before it is cancelled with CONTROL_FAILED (the controller stopped reporting), s.
  double execution_watchdog_timeout = 1.0;
  // ~start_state_max_bounds_error (MoveIt's FixStartStateBounds): a planning start state this far (rad or m)
  // or less outside a joint's limits is moved onto the limit (logged); further out it is START_STATE_INVALID.
  // Covers the numerical drift of measured joint states, e.g. a closed finger reading -2e-8 m.
  double start_state_max_bounds_error = 1e-3;
  double joint_state_timeout = 1.0;         // ~joint_state_timeout: how long a request waits for joint_states, s
  // ~longest_valid_segment_fraction (MoveIt's name): motions are collision-checked at this fraction of the
  // joint space's maximum extent, in (0, 1].
  double longest_valid_segment_fraction = 0.005;
  bool simplify_solutions = true;  // ~simplify_solutions: OMPL path simplification of every plan
  // ~trajectory_sample_period (MoveIt's resample_dt of its time-optimal parameterization adapter): s between the
  // points of planned trajectories (plan_kinematic_path, the move_group action), > 0. Controllers interpolate
  // between them with quintic splines of the points' positions, velocities and accelerations.
  double trajectory_sample_period = 0.1;
  OccupancyMapConfig occupancy_map;
};

// Reads every parameter the node needs from `nh` (its namespace) and `private_nh`. Throws ConfigError.
MoveGroupConfig loadConfig(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

// Cross-checks the configuration against the model (groups, joints, controllers). Fills joint limits the
// YAML leaves out from the URDF (velocity) and throws ConfigError when an active joint ends up without a
// velocity or acceleration limit, when a kinematics entry names an unknown group or solver, a controller
// an unknown joint or a joint already taken by another controller, or the grasping information does not fit the
// model (parseGraspingConfig).
void checkConfig(const sixdof_core::RobotModel& model, MoveGroupConfig* config);

}  // namespace sixdof_planning
