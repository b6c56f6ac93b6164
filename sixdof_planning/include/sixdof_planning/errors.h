#pragma once

#include <string>

#include <moveit_msgs/MoveItErrorCodes.h>
#include <sixdof_msgs/error_code_names.h>

namespace sixdof_planning {

// A MoveIt error code with the words moveit_msgs has no field for: `message` names what went wrong (the field,
// link, joint or object), `source` the component that decided. Assigning it to a response's error_code keeps the
// code; the words go to an action's status text or to move_group/error_reports (ErrorReporter).
struct ErrorCode : moveit_msgs::MoveItErrorCodes {
  std::string message;
  std::string source;
};

ErrorCode makeError(int val, const std::string& message, const std::string& source);
ErrorCode makeSuccess(const std::string& source, const std::string& message = "");
inline bool isSuccess(const ErrorCode& code) { return code.val == ErrorCode::SUCCESS; }
// `code` with a generic FAILURE replaced by `val`: a check shared by several fields (a pose, a number) fails with
// FAILURE, and the caller knows which code its field's failure is (INVALID_GOAL_CONSTRAINTS for a goal ...).
ErrorCode recode(ErrorCode code, int val);
// `code`, stored in the response's error_code too: what a service handler whose response carries one returns.
template <class Response>
ErrorCode answer(const ErrorCode& code, Response* response) {
  response->error_code = code;
  return code;
}

// The symbolic name of a code ("GOAL_IN_COLLISION"), for log lines: sixdof_msgs' one table of the names.
using sixdof_msgs::errorCodeName;

}  // namespace sixdof_planning
