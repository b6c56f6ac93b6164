#pragma once
// sixdof_sim/{reset_world, pause_physics, unpause_physics, step}: control of the simulation loop.

#include <ros/node_handle.h>
#include <ros/service_server.h>
#include <sixdof_msgs/StepSimulation.h>
#include <std_srvs/Empty.h>

#include <cstdint>
#include <functional>
#include <string>

namespace sixdof_sim {

// What the services act on (the node's loop).
struct SimControl {
  std::function<void()> reset;
  std::function<void(bool)> set_paused;
  std::function<bool()> paused;
  std::function<void(std::uint64_t)> step;
};

class SimControlServices {
 public:
  SimControlServices(ros::NodeHandle nh, SimControl control);

 private:
  bool reset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool step(sixdof_msgs::StepSimulation::Request& req, sixdof_msgs::StepSimulation::Response& res);

  SimControl control_;
  ros::ServiceServer reset_, pause_, unpause_, step_;
};

}  // namespace sixdof_sim
