#include "conveyor_services.h"

#include <ros/console.h>
#include <sixdof_msgs/ConveyorStates.h>

#include <cmath>

namespace sixdof_sim {

ConveyorServices::ConveyorServices(ros::NodeHandle sim_nh, ros::NodeHandle nh, World& world)
    : world_(world),
      set_conveyor_(sim_nh.advertiseService("set_conveyor", &ConveyorServices::setConveyor, this)),
      states_pub_(sim_nh.advertise<sixdof_msgs::ConveyorStates>("conveyor_states", 10)) {
  if (!world_.suctionAvailable()) return;
  vacuum_server_ =
      std::make_unique<Server>(ros::NodeHandle(nh, world_.suctionConfig()->controller), "gripper_cmd", false);
  vacuum_server_->registerGoalCallback([this](Server::GoalHandle goal) { vacuumGoal(goal); });
  vacuum_server_->registerCancelCallback([this](Server::GoalHandle goal) { vacuumCancel(goal); });
  vacuum_server_->start();
}

bool ConveyorServices::setConveyor(sixdof_msgs::SetConveyor::Request& req, sixdof_msgs::SetConveyor::Response& res) {
  const Result r = world_.setConveyorSpeed(req.name, req.speed);
  res.success = r.ok();
  res.status_message = r.ok() ? "conveyor '" + req.name + "' at " + std::to_string(req.speed) + " m/s" : r.message;
  if (!r.ok()) ROS_WARN_STREAM("[sixdof_sim] set_conveyor: " << r.message);
  return true;
}

control_msgs::GripperCommandResult ConveyorServices::vacuumResult() const {
  control_msgs::GripperCommandResult result;
  result.position = world_.vacuum() ? 1.0 : 0.0;
  result.stalled = !world_.suctionHeld().empty();
  result.reached_goal = true;
  return result;
}

void ConveyorServices::vacuumGoal(Server::GoalHandle goal) {
  const control_msgs::GripperCommand& command = goal.getGoal()->command;
  if (!std::isfinite(command.position) || !std::isfinite(command.max_effort) || command.max_effort < 0.0) {
    const std::string message = "command.position must be finite and command.max_effort finite and >= 0";
    ROS_WARN_STREAM("[" << world_.suctionConfig()->controller << "/gripper_cmd] goal rejected: " << message);
    goal.setRejected(vacuumResult(), message);
    return;
  }
  if (vacuum_goal_) vacuum_goal_->setCanceled(vacuumResult(), "preempted by a new goal");
  goal.setAccepted();
  world_.setVacuum(command.position > 0.0);
  vacuum_goal_ = goal;
}

void ConveyorServices::vacuumCancel(Server::GoalHandle goal) {
  if (!vacuum_goal_ || !(*vacuum_goal_ == goal)) return;
  vacuum_goal_->setCanceled(vacuumResult(), "canceled");
  vacuum_goal_.reset();
}

void ConveyorServices::afterStep() {
  if (vacuum_goal_) {
    vacuum_goal_->setSucceeded(vacuumResult(), world_.vacuum() ? "vacuum on" : "vacuum off");
    vacuum_goal_.reset();
  }
  if (world_.suctionAvailable() && world_.suctionRefused() != refused_) {
    refused_ = world_.suctionRefused();
    ObjectState state;
    if (!refused_.empty() && world_.objectState(refused_, &state).ok()) {
      ROS_WARN_STREAM("[sixdof_sim] suction: '" << refused_ << "' (" << state.spec.mass << " kg) is over the cup's "
                                                << "max_payload of " << world_.suctionConfig()->max_payload
                                                << " kg: not held");
    }
  }
  for (const std::string& sunk : world_.takeSunkObjects()) {
    ROS_INFO_STREAM("[sixdof_sim] sink " << sunk.substr(0, sunk.find(':')) << " deleted '"
                                         << sunk.substr(sunk.find(':') + 1) << "'");
  }
}

void ConveyorServices::publish(const ros::Time& stamp) {
  if (world_.conveyorStates().empty() && world_.sourceStates().empty() && world_.sinkStates().empty()) return;
  sixdof_msgs::ConveyorStates msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = "world";
  for (const ConveyorState& c : world_.conveyorStates()) {
    msg.conveyor.push_back(c.name);
    msg.speed.push_back(c.speed);
    geometry_msgs::Vector3 v;
    v.x = c.velocity.x();
    v.y = c.velocity.y();
    v.z = c.velocity.z();
    msg.velocity.push_back(v);
  }
  for (const SourceState& s : world_.sourceStates()) {
    msg.source.push_back(s.name);
    msg.spawned.push_back(s.spawned);
  }
  for (const SinkState& s : world_.sinkStates()) {
    msg.sink.push_back(s.name);
    msg.deleted.push_back(s.deleted);
  }
  states_pub_.publish(msg);
}

}  // namespace sixdof_sim
