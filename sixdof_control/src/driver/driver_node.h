#pragma once
// The sixdof_control driver node: the controllers of controllers.yaml on a hardware plugin, through the control loop,
// served over ROS as the simulator serves them (controller_actions.h), plus joint_states (mimic joints included),
// ~estop, ~clear_fault and the loop's diagnostics. docs/real_robot.md is the user's side.

#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/service_server.h>
#include <ros/wall_timer.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include <memory>
#include <string>
#include <vector>

#include "loop_host.h"
#include "sixdof_control/control_loop.h"
#include "sixdof_control/controller_actions.h"
#include "sixdof_control/hardware_loader.h"

namespace sixdof_control {

// A joint of joint_states: a hardware joint, or a mimic joint following one.
struct PublishedJoint {
  std::string name;
  std::size_t source;  // index into the hardware's joints
  double multiplier = 1.0;
  double offset = 0.0;
};

class DriverNode {
 public:
  // Reads every parameter, loads and starts the hardware and the loop; throws std::runtime_error (or
  // std::invalid_argument) naming the problem: a bad parameter, a plugin that cannot be loaded or fails to init or
  // start.
  DriverNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  // Stops the loop (active goals abort) and the hardware.
  ~DriverNode();
  DriverNode(const DriverNode&) = delete;
  DriverNode& operator=(const DriverNode&) = delete;

 private:
  void publish();
  void publishDiagnostics();
  bool estop(std_srvs::SetBool::Request& request, std_srvs::SetBool::Response& response);
  bool clearFault(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  std::string plugin_;
  std::vector<PublishedJoint> published_;
  HardwareLoader loader_;
  pluginlib::UniquePtr<HardwareInterface> hardware_;
  std::unique_ptr<ControlLoop> loop_;
  std::unique_ptr<LoopHost> host_;
  std::unique_ptr<ControllerActions> actions_;
  LoopState last_state_ = LoopState::kRunning;
  ros::Publisher joint_state_pub_, diagnostics_pub_;
  ros::ServiceServer estop_service_, clear_fault_service_;
  ros::WallTimer publish_timer_, diagnostics_timer_;
};

}  // namespace sixdof_control
