#pragma once

#include <string>

#include <sixdof_msgs/MoveItErrorCodes.h>

namespace sixdof_planning {

using ErrorCode = sixdof_msgs::MoveItErrorCodes;

ErrorCode makeError(int val, const std::string& message, const std::string& source);
ErrorCode makeSuccess(const std::string& source, const std::string& message = "");
inline bool isSuccess(const ErrorCode& code) { return code.val == ErrorCode::SUCCESS; }

// The symbolic name of a code ("GOAL_IN_COLLISION"), for log lines.
std::string errorCodeName(int val);

}  // namespace sixdof_planning
