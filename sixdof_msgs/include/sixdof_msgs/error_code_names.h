// The names of moveit_msgs/MoveItErrorCodes' values, for log lines and status texts. Header only, so that
// move_group, the rviz plugins and any other C++ user share one table without a library to link.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <moveit_msgs/MoveItErrorCodes.h>

namespace sixdof_msgs {

struct MoveItErrorCodeName {
  int32_t val;
  const char* name;
};

// Every constant of moveit_msgs/MoveItErrorCodes (moveit_msgs 0.11.4), in the message's order; test_error_code_names
// checks it against the message definition.
inline constexpr std::array<MoveItErrorCodeName, 30> kMoveItErrorCodeNames = {{
    {moveit_msgs::MoveItErrorCodes::SUCCESS, "SUCCESS"},
    {moveit_msgs::MoveItErrorCodes::FAILURE, "FAILURE"},
    {moveit_msgs::MoveItErrorCodes::PLANNING_FAILED, "PLANNING_FAILED"},
    {moveit_msgs::MoveItErrorCodes::INVALID_MOTION_PLAN, "INVALID_MOTION_PLAN"},
    {moveit_msgs::MoveItErrorCodes::MOTION_PLAN_INVALIDATED_BY_ENVIRONMENT_CHANGE,
     "MOTION_PLAN_INVALIDATED_BY_ENVIRONMENT_CHANGE"},
    {moveit_msgs::MoveItErrorCodes::CONTROL_FAILED, "CONTROL_FAILED"},
    {moveit_msgs::MoveItErrorCodes::UNABLE_TO_AQUIRE_SENSOR_DATA, "UNABLE_TO_AQUIRE_SENSOR_DATA"},
    {moveit_msgs::MoveItErrorCodes::TIMED_OUT, "TIMED_OUT"},
    {moveit_msgs::MoveItErrorCodes::PREEMPTED, "PREEMPTED"},
    {moveit_msgs::MoveItErrorCodes::START_STATE_IN_COLLISION, "START_STATE_IN_COLLISION"},
    {moveit_msgs::MoveItErrorCodes::START_STATE_VIOLATES_PATH_CONSTRAINTS, "START_STATE_VIOLATES_PATH_CONSTRAINTS"},
    {moveit_msgs::MoveItErrorCodes::START_STATE_INVALID, "START_STATE_INVALID"},
    {moveit_msgs::MoveItErrorCodes::GOAL_IN_COLLISION, "GOAL_IN_COLLISION"},
    {moveit_msgs::MoveItErrorCodes::GOAL_VIOLATES_PATH_CONSTRAINTS, "GOAL_VIOLATES_PATH_CONSTRAINTS"},
    {moveit_msgs::MoveItErrorCodes::GOAL_CONSTRAINTS_VIOLATED, "GOAL_CONSTRAINTS_VIOLATED"},
    {moveit_msgs::MoveItErrorCodes::GOAL_STATE_INVALID, "GOAL_STATE_INVALID"},
    {moveit_msgs::MoveItErrorCodes::UNRECOGNIZED_GOAL_TYPE, "UNRECOGNIZED_GOAL_TYPE"},
    {moveit_msgs::MoveItErrorCodes::INVALID_GROUP_NAME, "INVALID_GROUP_NAME"},
    {moveit_msgs::MoveItErrorCodes::INVALID_GOAL_CONSTRAINTS, "INVALID_GOAL_CONSTRAINTS"},
    {moveit_msgs::MoveItErrorCodes::INVALID_ROBOT_STATE, "INVALID_ROBOT_STATE"},
    {moveit_msgs::MoveItErrorCodes::INVALID_LINK_NAME, "INVALID_LINK_NAME"},
    {moveit_msgs::MoveItErrorCodes::INVALID_OBJECT_NAME, "INVALID_OBJECT_NAME"},
    {moveit_msgs::MoveItErrorCodes::FRAME_TRANSFORM_FAILURE, "FRAME_TRANSFORM_FAILURE"},
    {moveit_msgs::MoveItErrorCodes::COLLISION_CHECKING_UNAVAILABLE, "COLLISION_CHECKING_UNAVAILABLE"},
    {moveit_msgs::MoveItErrorCodes::ROBOT_STATE_STALE, "ROBOT_STATE_STALE"},
    {moveit_msgs::MoveItErrorCodes::SENSOR_INFO_STALE, "SENSOR_INFO_STALE"},
    {moveit_msgs::MoveItErrorCodes::COMMUNICATION_FAILURE, "COMMUNICATION_FAILURE"},
    {moveit_msgs::MoveItErrorCodes::CRASH, "CRASH"},
    {moveit_msgs::MoveItErrorCodes::ABORT, "ABORT"},
    {moveit_msgs::MoveItErrorCodes::NO_IK_SOLUTION, "NO_IK_SOLUTION"},
}};

// The constant's name ("GOAL_IN_COLLISION"); a value that is none of them: "unknown MoveIt error code <val>".
inline std::string errorCodeName(int32_t val) {
  for (const auto& entry : kMoveItErrorCodeNames) {
    if (entry.val == val) return entry.name;
  }
  return "unknown MoveIt error code " + std::to_string(val);
}

}  // namespace sixdof_msgs
