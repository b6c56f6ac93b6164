#include "sixdof_planning/state_monitor.h"

#include <chrono>
#include <cmath>

namespace sixdof_planning {

CurrentStateMonitor::CurrentStateMonitor(ros::NodeHandle& nh, sixdof_core::RobotModelConstPtr model,
                                         const std::string& topic)
    : model_(std::move(model)) {
  subscriber_ = nh.subscribe<sensor_msgs::JointState>(
      topic, 10, [this](const sensor_msgs::JointState::ConstPtr& msg) { update(*msg); });
}

void CurrentStateMonitor::update(const sensor_msgs::JointState& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  const size_t n = std::min(msg.name.size(), msg.position.size());
  for (size_t i = 0; i < n; ++i) {
    const int index = model_->jointIndex(msg.name[i]);
    // Unknown joints (another robot on the topic) and mimic joints (derived from their source) are not ours.
    if (index < 0 || !model_->joints()[index].isActive() || !std::isfinite(msg.position[i])) continue;
    positions_[msg.name[i]] = msg.position[i];
  }
  last_update_ = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
  changed_.notify_all();
}

std::vector<std::string> CurrentStateMonitor::missingJoints() const {
  std::vector<std::string> missing;
  for (const auto& name : model_->variableNames()) {
    if (!positions_.count(name)) missing.push_back(name);
  }
  return missing;
}

bool CurrentStateMonitor::currentState(double timeout, sixdof_core::RobotState* state,
                                       std::vector<std::string>* missing) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  std::vector<std::string> absent = missingJoints();
  while (!absent.empty() && changed_.wait_until(lock, deadline) != std::cv_status::timeout) {
    absent = missingJoints();
  }
  absent = missingJoints();
  Eigen::VectorXd positions = state->positions();
  for (size_t i = 0; i < model_->variableCount(); ++i) {
    const auto it = positions_.find(model_->variableNames()[i]);
    if (it != positions_.end()) positions[i] = it->second;
  }
  lock.unlock();
  state->setPositions(positions);
  if (!absent.empty()) {
    if (missing) *missing = absent;
    return false;
  }
  return true;
}

ros::Time CurrentStateMonitor::lastUpdate() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_update_;
}

}  // namespace sixdof_planning
