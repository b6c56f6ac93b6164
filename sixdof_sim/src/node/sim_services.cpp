#include "sim_services.h"

#include <ros/console.h>

namespace sixdof_sim {

// Steps requested at once are bounded so that one call cannot block the node for minutes.
constexpr std::uint32_t kMaxStepsPerCall = 100000;

SimControlServices::SimControlServices(ros::NodeHandle nh, SimControl control)
    : control_(std::move(control)),
      reset_(nh.advertiseService("reset_world", &SimControlServices::reset, this)),
      pause_(nh.advertiseService("pause_physics", &SimControlServices::pause, this)),
      unpause_(nh.advertiseService("unpause_physics", &SimControlServices::unpause, this)),
      step_(nh.advertiseService("step", &SimControlServices::step, this)) {}

bool SimControlServices::reset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  control_.reset();
  ROS_INFO("[sixdof_sim] world reset");
  return true;
}

bool SimControlServices::pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  control_.set_paused(true);
  return true;
}

bool SimControlServices::unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  control_.set_paused(false);
  return true;
}

bool SimControlServices::step(sixdof_msgs::StepSimulation::Request& req, sixdof_msgs::StepSimulation::Response& res) {
  if (!control_.paused()) {
    res.success = false;
    res.status_message = "step: the simulation is running; call pause_physics first";
  } else if (req.steps == 0 || req.steps > kMaxStepsPerCall) {
    res.success = false;
    res.status_message = "step: steps must be in [1, " + std::to_string(kMaxStepsPerCall) + "], got " +
                         std::to_string(req.steps);
  } else {
    control_.step(req.steps);
    res.success = true;
    res.status_message = "advanced " + std::to_string(req.steps) + " steps";
  }
  return true;
}

}  // namespace sixdof_sim
