#pragma once
// Feedback and goal endings shared by the two action capabilities (move_group, execute_trajectory).

#include <string>

#include <ros/console.h>

#include "sixdof_planning/errors.h"

namespace sixdof_planning {

template <typename Feedback, typename Server>
void publishState(Server* server, const std::string& state) {
  Feedback feedback;
  feedback.state = state;
  server->publishFeedback(feedback);
}

// Ends the server's current goal by `code` (PREEMPTED -> preempted, success -> succeeded, else aborted) with the
// code in the result and its words as the goal's status text (where actionlib clients read them), logs it under
// `source` and reports the server idle.
template <typename Feedback, typename Server, typename Result>
void finishGoal(Server* server, Result* result, const ErrorCode& code, const char* source) {
  result->error_code = code;
  ROS_INFO_STREAM(source << ": " << errorCodeName(code.val) << " " << code.message);
  if (code.val == ErrorCode::PREEMPTED) {
    server->setPreempted(*result, code.message);
  } else if (isSuccess(code)) {
    server->setSucceeded(*result, code.message);
  } else {
    server->setAborted(*result, code.message);
  }
  publishState<Feedback>(server, "IDLE");
}

}  // namespace sixdof_planning
