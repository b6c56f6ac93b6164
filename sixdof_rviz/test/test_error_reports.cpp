// ErrorReports: the reports of move_group/error_reports that belong to a call of this node (rostest: a master; the
// reports are published here, as move_group publishes them).
#include <string>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "sixdof_rviz/error_reports.h"

namespace sixdof_rviz {
namespace {

// Hang guard only: a message on a local connection arrives in milliseconds.
constexpr double kArrival = 10.0;

sixdof_msgs::ErrorReport makeReport(const std::string& caller, const std::string& interface,
                                    const std::string& message, const std::string& source = "") {
  sixdof_msgs::ErrorReport report;
  report.header.stamp = ros::Time::now();
  report.caller_id = caller;
  report.interface = interface;
  report.error_code.val = moveit_msgs::MoveItErrorCodes::INVALID_GROUP_NAME;
  report.message = message;
  report.source = source;
  return report;
}

class ErrorReportsTest : public ::testing::Test {
 protected:
  ErrorReportsTest() : reports_(nh_) {
    pub_ = nh_.advertise<sixdof_msgs::ErrorReport>(kErrorReportTopic, 10);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kArrival);
    while (pub_.getNumSubscribers() == 0 && ros::WallTime::now() < deadline) ros::WallDuration(0.01).sleep();
  }

  // Publishes `report` and waits until ErrorReports has taken it (it counts only this node's reports).
  void publishOwn(const sixdof_msgs::ErrorReport& report) {
    const uint64_t before = reports_.mark();
    pub_.publish(report);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kArrival);
    while (reports_.mark() == before && ros::WallTime::now() < deadline) ros::WallDuration(0.01).sleep();
    ASSERT_GT(reports_.mark(), before) << "the report did not arrive";
  }

  ros::NodeHandle nh_;
  ErrorReports reports_;
  ros::Publisher pub_;
};

TEST_F(ErrorReportsTest, FindsTheReportOfThisNodesCallAfterTheMark) {
  EXPECT_EQ(reports_.topic(), "/move_group/error_reports");
  const std::string me = ros::this_node::getName();
  publishOwn(makeReport(me, "/compute_ik", "an earlier call's report"));
  const uint64_t mark = reports_.mark();
  pub_.publish(makeReport("/someone_else", "/compute_ik", "another node's report"));
  pub_.publish(makeReport(me, "/check_state_validity", "another interface's report"));
  pub_.publish(makeReport(me, "/compute_ik", "group 'legs' is not a planning group", "compute_ik"));
  const auto report = reports_.waitFor("/compute_ik", mark, kArrival);
  ASSERT_TRUE(report);
  EXPECT_EQ(report->message, "group 'legs' is not a planning group");
  EXPECT_EQ(describeReport(*report), "group 'legs' is not a planning group [compute_ik]");
  EXPECT_EQ(reports_.explainFailure("no IK solution", "/compute_ik", mark),
            "no IK solution: group 'legs' is not a planning group [compute_ik]");
}

TEST_F(ErrorReportsTest, NoReportForTheCallIsNoneAfterTheWait) {
  const std::string me = ros::this_node::getName();
  publishOwn(makeReport(me, "/plan_kinematic_path", "before the mark"));
  const uint64_t mark = reports_.mark();
  publishOwn(makeReport(me, "/compute_fk", "another interface"));
  EXPECT_FALSE(reports_.waitFor("/plan_kinematic_path", mark, 0.2));
  EXPECT_EQ(reports_.explainFailure("call failed", "/plan_kinematic_path", mark),
            "call failed (no error report from move_group on /move_group/error_reports)");
  EXPECT_EQ(describeReport(makeReport(me, "/compute_fk", "no source")), "no source");
}

}  // namespace
}  // namespace sixdof_rviz
