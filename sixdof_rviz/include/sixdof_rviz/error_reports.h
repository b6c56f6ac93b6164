#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <ros/spinner.h>
#include <sixdof_msgs/ErrorReport.h>

namespace sixdof_rviz {

// Where move_group publishes a sixdof_msgs/ErrorReport for every request it refuses or fails (docs/design.md).
constexpr char kErrorReportTopic[] = "move_group/error_reports";
// How long a client waits, after a failed answer, for the report that goes with it. move_group publishes the
// report before it answers, so it is normally there already; the wait only covers the two connections' skew.
constexpr double kErrorReportWait = 1.0;

// The words of move_group's failed answers to this node: moveit_msgs' service responses carry at most a code, the
// message naming the problem comes as an ErrorReport. Keeps the recent reports whose caller_id is this node
// (ros::this_node::getName()), received on its own callback queue and thread, so that a caller blocked in a
// service call (the GUI thread, a worker) can wait for one.
//
//   const auto mark = reports.mark();
//   client.call(srv);                  // failed
//   auto report = reports.waitFor(client.getService(), mark, kErrorReportWait);
class ErrorReports {
 public:
  // Subscribes to `topic`, resolved in `nh`'s namespace.
  explicit ErrorReports(const ros::NodeHandle& nh, const std::string& topic = kErrorReportTopic);
  ~ErrorReports();
  ErrorReports(const ErrorReports&) = delete;
  ErrorReports& operator=(const ErrorReports&) = delete;

  // Taken before a call: only reports received after it can belong to that call. The first mark waits up to
  // kConnectWait seconds for a publisher of the topic to connect, so that the reports of a call made right after
  // construction are not missed (a publisher that is there connects in milliseconds). One caller thread at a time.
  uint64_t mark();
  // The first report for `interface` (a resolved name, e.g. "/compute_ik") received after `mark`, waiting up to
  // `timeout` seconds for it; nullopt when none came.
  std::optional<sixdof_msgs::ErrorReport> waitFor(const std::string& interface, uint64_t mark, double timeout) const;
  // "<what>: <the report's words>" for the first report for `interface` after `mark` (waiting up to
  // kErrorReportWait), or "<what> (no error report from move_group on <topic>)".
  std::string explainFailure(const std::string& what, const std::string& interface, uint64_t mark) const;
  // The resolved topic.
  const std::string& topic() const { return topic_; }

  // Reports kept; older ones are dropped.
  static constexpr size_t kKept = 64;
  static constexpr double kConnectWait = 0.5;

 private:
  struct Received {
    uint64_t sequence;
    sixdof_msgs::ErrorReport report;
  };
  void receive(const sixdof_msgs::ErrorReport::ConstPtr& report);

  std::string node_name_;
  std::string topic_;
  ros::CallbackQueue queue_;
  ros::Subscriber sub_;
  ros::AsyncSpinner spinner_;
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  uint64_t received_ = 0;
  bool connection_awaited_ = false;
  std::deque<Received> reports_;
};

// A report as one status text: "<message> [<source>]" (the source only when given).
std::string describeReport(const sixdof_msgs::ErrorReport& report);

}  // namespace sixdof_rviz
