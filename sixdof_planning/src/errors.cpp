#include "sixdof_planning/errors.h"

#include <map>

namespace sixdof_planning {

ErrorCode makeError(int val, const std::string& message, const std::string& source) {
  ErrorCode code;
  code.val = val;
  code.message = message;
  code.source = source;
  return code;
}

ErrorCode makeSuccess(const std::string& source, const std::string& message) {
  return makeError(ErrorCode::SUCCESS, message, source);
}

ErrorCode recode(ErrorCode code, int val) {
  if (code.val == ErrorCode::FAILURE) code.val = val;
  return code;
}

std::string errorCodeName(int val) {
  static const std::map<int, std::string> names = {
      {ErrorCode::SUCCESS, "SUCCESS"},
      {ErrorCode::FAILURE, "FAILURE"},
      {ErrorCode::PLANNING_FAILED, "PLANNING_FAILED"},
      {ErrorCode::INVALID_MOTION_PLAN, "INVALID_MOTION_PLAN"},
      {ErrorCode::MOTION_PLAN_INVALIDATED_BY_ENVIRONMENT_CHANGE, "MOTION_PLAN_INVALIDATED_BY_ENVIRONMENT_CHANGE"},
      {ErrorCode::CONTROL_FAILED, "CONTROL_FAILED"},
      {ErrorCode::UNABLE_TO_AQUIRE_SENSOR_DATA, "UNABLE_TO_AQUIRE_SENSOR_DATA"},
      {ErrorCode::TIMED_OUT, "TIMED_OUT"},
      {ErrorCode::PREEMPTED, "PREEMPTED"},
      {ErrorCode::START_STATE_IN_COLLISION, "START_STATE_IN_COLLISION"},
      {ErrorCode::START_STATE_VIOLATES_PATH_CONSTRAINTS, "START_STATE_VIOLATES_PATH_CONSTRAINTS"},
      {ErrorCode::START_STATE_INVALID, "START_STATE_INVALID"},
      {ErrorCode::GOAL_IN_COLLISION, "GOAL_IN_COLLISION"},
      {ErrorCode::GOAL_VIOLATES_PATH_CONSTRAINTS, "GOAL_VIOLATES_PATH_CONSTRAINTS"},
      {ErrorCode::GOAL_CONSTRAINTS_VIOLATED, "GOAL_CONSTRAINTS_VIOLATED"},
      {ErrorCode::GOAL_STATE_INVALID, "GOAL_STATE_INVALID"},
      {ErrorCode::UNRECOGNIZED_GOAL_TYPE, "UNRECOGNIZED_GOAL_TYPE"},
      {ErrorCode::INVALID_GROUP_NAME, "INVALID_GROUP_NAME"},
      {ErrorCode::INVALID_GOAL_CONSTRAINTS, "INVALID_GOAL_CONSTRAINTS"},
      {ErrorCode::INVALID_ROBOT_STATE, "INVALID_ROBOT_STATE"},
      {ErrorCode::INVALID_LINK_NAME, "INVALID_LINK_NAME"},
      {ErrorCode::INVALID_OBJECT_NAME, "INVALID_OBJECT_NAME"},
      {ErrorCode::FRAME_TRANSFORM_FAILURE, "FRAME_TRANSFORM_FAILURE"},
      {ErrorCode::COLLISION_CHECKING_UNAVAILABLE, "COLLISION_CHECKING_UNAVAILABLE"},
      {ErrorCode::ROBOT_STATE_STALE, "ROBOT_STATE_STALE"},
      {ErrorCode::SENSOR_INFO_STALE, "SENSOR_INFO_STALE"},
      {ErrorCode::COMMUNICATION_FAILURE, "COMMUNICATION_FAILURE"},
      {ErrorCode::CRASH, "CRASH"},
      {ErrorCode::ABORT, "ABORT"},
      {ErrorCode::NO_IK_SOLUTION, "NO_IK_SOLUTION"},
  };
  auto it = names.find(val);
  return it == names.end() ? "code " + std::to_string(val) : it->second;
}

}  // namespace sixdof_planning
