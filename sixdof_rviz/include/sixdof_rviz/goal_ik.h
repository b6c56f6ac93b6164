#pragma once

#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "sixdof_rviz/error_reports.h"
#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

struct GoalIkRequest {
  geometry_msgs::PoseStamped pose;
  std::string group;
  std::string tip_link;
  sensor_msgs::JointState seed;
};

struct GoalIkOutcome {
  enum class Kind { kValid, kInCollision, kNoSolution, kError };
  Kind kind = Kind::kError;
  JointValues solution;  // the IK solution's joints (empty without one)
  std::string message;   // for the status line; move_group's words when it refused or failed
};

// The Goal State display's IK: move_group's compute_ik for the dragged pose (collisions not avoided, so that a
// colliding goal is still shown), then check_state_validity for the solution. Blocking; the display calls it from
// its worker thread. move_group's words for a failed call come from its error reports.
class GoalIk {
 public:
  // `nh`: the namespace of move_group's interfaces.
  explicit GoalIk(const ros::NodeHandle& nh);

  GoalIkOutcome solve(const GoalIkRequest& request);

 private:
  // Why a call failed: the service is missing, or move_group's report.
  std::string callFailure(ros::ServiceClient& client, uint64_t mark) const;

  ros::NodeHandle nh_;
  ErrorReports reports_;
};

}  // namespace sixdof_rviz
