#include "sixdof_planning/state_monitor.h"

#include <cmath>
#include <limits>

namespace sixdof_planning {

namespace {

double secondsSince(std::chrono::steady_clock::time_point then) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - then).count();
}

}  // namespace

CurrentStateMonitor::CurrentStateMonitor(ros::NodeHandle& nh, sixdof_core::RobotModelConstPtr model,
                                         const std::string& topic)
    : model_(std::move(model)) {
  ros::NodeHandle own(nh);
  own.setCallbackQueue(&queue_);
  subscriber_ = own.subscribe<sensor_msgs::JointState>(
      topic, 10, [this](const sensor_msgs::JointState::ConstPtr& msg) { update(*msg); });
  if (ros::Time::isSimTime()) {
    clock_subscriber_ = own.subscribe<rosgraph_msgs::Clock>(
        "/clock", 1, [this](const rosgraph_msgs::Clock::ConstPtr& msg) { clockUpdate(*msg); });
  }
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

CurrentStateMonitor::~CurrentStateMonitor() {
  spinner_->stop();
  subscriber_.shutdown();
  clock_subscriber_.shutdown();
}

void CurrentStateMonitor::update(const sensor_msgs::JointState& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  const size_t n = std::min(msg.name.size(), msg.position.size());
  bool ours = false;
  for (size_t i = 0; i < n; ++i) {
    const int index = model_->jointIndex(msg.name[i]);
    // Unknown joints (another robot on the topic) and mimic joints (derived from their source) are not ours.
    if (index < 0 || !model_->joints()[index].isActive() || !std::isfinite(msg.position[i])) continue;
    positions_[msg.name[i]] = msg.position[i];
    ours = true;
  }
  if (ours) {
    received_ = true;
    last_update_ = Clock::now();
    last_stamp_ = msg.header.stamp;
  }
  changed_.notify_all();
}

void CurrentStateMonitor::clockUpdate(const rosgraph_msgs::Clock& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  // Any change counts, backwards too: a restarted simulator starts its clock again at zero.
  if (!clock_received_ || msg.clock != last_clock_) {
    clock_received_ = true;
    last_clock_ = msg.clock;
    last_clock_advance_ = Clock::now();
  }
}

StateLiveness CurrentStateMonitor::liveness() const {
  constexpr double kNever = std::numeric_limits<double>::infinity();
  std::lock_guard<std::mutex> lock(mutex_);
  StateLiveness live;
  live.joint_states_age = received_ ? secondsSince(last_update_) : kNever;
  live.clock_still = !ros::Time::isSimTime() ? 0.0 : clock_received_ ? secondsSince(last_clock_advance_) : kNever;
  return live;
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
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout);
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

bool CurrentStateMonitor::waitForStateNewerThan(const ros::Time& time, double timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout);
  while (last_stamp_ < time) {
    if (!received_ || last_stamp_.isZero()) return false;  // nothing yet, or unstamped messages
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout) return last_stamp_ >= time;
  }
  return true;
}

bool CurrentStateMonitor::waitForPositions(const std::function<bool(const std::map<std::string, double>&)>& reached,
                                           double timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout);
  return changed_.wait_until(lock, deadline, [&] { return reached(positions_); });
}

}  // namespace sixdof_planning
