#pragma once
// The sixdof_sim node: runs the Bullet World at a fixed step paced to a real-time factor, drives it with
// the trajectory/gripper controllers (sim_controllers.h, served by sixdof_control's controller_actions.h) and
// publishes its state. Single-threaded: ROS callbacks run between
// physics steps, so the World is never touched concurrently.

#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera_publisher.h"
#include "conveyor_services.h"
#include "object_services.h"
#include "sim_controllers.h"
#include "sim_services.h"
#include "sixdof_control/controller_actions.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

struct SimNodeOptions {
  std::string world_file;        // empty: no objects besides the ground
  double physics_step = 0.001;   // s
  double real_time_factor = 1.0; // 0: as fast as possible
  bool grasp_fix = true;
  // Hz of simulated time: joint_states, object_states, tf (at most this many per wall-clock second too), action
  // feedback.
  double publish_rate = 100.0;
};

class SimNode {
 public:
  // Reads all parameters once; throws std::runtime_error naming the problem on bad configuration.
  SimNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~SimNode();
  void run();

 private:
  static SimNodeOptions readOptions(const ros::NodeHandle& pnh);
  double now() const { return clock_offset_ + world_->simTime(); }
  void stepOnce();
  void publishState();
  void publishClock(bool force);
  void reset();
  void setPaused(bool paused);
  void checkpointClock();

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  SimNodeOptions options_;
  std::unique_ptr<World> world_;
  // World::reset() restarts its time at zero; /clock must not jump back, so resets accumulate an offset.
  double clock_offset_ = 0.0;
  // ~clock_checkpoint on the parameter server: a time /clock has not reached yet, refreshed every
  // kCheckpointPeriod of wall time. A restarted simulator resumes from it (see SimNode::SimNode).
  std::chrono::steady_clock::time_point last_checkpoint_wall_;
  double last_checkpoint_sim_ = 0.0;
  bool paused_ = false;
  double next_publish_ = 0.0;
  double next_state_ = 0.0;  // joint_states, object_states, tf: due at this simulated time and
  std::chrono::steady_clock::time_point next_state_wall_;  // this wall time
  std::chrono::steady_clock::time_point last_clock_wall_;
  // Pacing anchor: sim time `pace_sim_` was reached at wall time `pace_wall_`.
  std::chrono::steady_clock::time_point pace_wall_;
  double pace_sim_ = 0.0;

  // The controllers (sixdof_control's readControllerSetup: controller_list, ~controllers,
  // ~gripper_command_controller), their ROS interface, and the cameras, which render before each physics step.
  std::unique_ptr<SimControllers> controllers_;
  std::unique_ptr<sixdof_control::ControllerActions> actions_;
  std::unique_ptr<CameraPublisher> cameras_;
  std::unique_ptr<ObjectServices> object_services_;
  std::unique_ptr<SimControlServices> control_services_;
  std::unique_ptr<ConveyorServices> conveyor_services_;
  ros::Publisher clock_pub_, joint_state_pub_, object_state_pub_, grasp_event_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_tf_broadcaster_;
};

}  // namespace sixdof_sim
