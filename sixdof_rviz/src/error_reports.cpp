#include "sixdof_rviz/error_reports.h"

#include <chrono>

namespace sixdof_rviz {

ErrorReports::ErrorReports(const ros::NodeHandle& nh, const std::string& topic)
    : node_name_(ros::this_node::getName()), topic_(nh.resolveName(topic)), spinner_(1, &queue_) {
  ros::SubscribeOptions options = ros::SubscribeOptions::create<sixdof_msgs::ErrorReport>(
      topic_, static_cast<uint32_t>(kKept), [this](const sixdof_msgs::ErrorReport::ConstPtr& r) { receive(r); },
      ros::VoidPtr(), &queue_);
  sub_ = ros::NodeHandle(nh).subscribe(options);
  spinner_.start();
}

ErrorReports::~ErrorReports() {
  spinner_.stop();
  sub_.shutdown();
}

void ErrorReports::receive(const sixdof_msgs::ErrorReport::ConstPtr& report) {
  if (report->caller_id != node_name_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    reports_.push_back(Received{++received_, *report});
    if (reports_.size() > kKept) reports_.pop_front();
  }
  arrived_.notify_all();
}

uint64_t ErrorReports::mark() {
  if (!connection_awaited_) {
    connection_awaited_ = true;
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kConnectWait);
    while (sub_.getNumPublishers() == 0 && ros::WallTime::now() < deadline) ros::WallDuration(0.01).sleep();
  }
  std::lock_guard<std::mutex> lock(mutex_);
  return received_;
}

std::optional<sixdof_msgs::ErrorReport> ErrorReports::waitFor(const std::string& interface, uint64_t mark,
                                                              double timeout) const {
  std::optional<sixdof_msgs::ErrorReport> found;
  const auto match = [&] {
    for (const auto& received : reports_) {
      if (received.sequence > mark && received.report.interface == interface) {
        found = received.report;
        return true;
      }
    }
    return false;
  };
  std::unique_lock<std::mutex> lock(mutex_);
  arrived_.wait_for(lock, std::chrono::duration<double>(timeout), match);
  return found;
}

std::string ErrorReports::explainFailure(const std::string& what, const std::string& interface,
                                         uint64_t mark) const {
  const auto report = waitFor(interface, mark, kErrorReportWait);
  if (report) return what + ": " + describeReport(*report);
  return what + " (no error report from move_group on " + topic_ + ")";
}

std::string describeReport(const sixdof_msgs::ErrorReport& report) {
  return report.source.empty() ? report.message : report.message + " [" + report.source + "]";
}

}  // namespace sixdof_rviz
