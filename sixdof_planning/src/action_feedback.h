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

// Ends the server's current goal by its error code (PREEMPTED -> preempted, success -> succeeded, else aborted),
// logs it under `source` and reports the server idle.
template <typename Feedback, typename Server, typename Result>
void finishGoal(Server* server, const Result& result, const char* source) {
  ROS_INFO_STREAM(source << ": " << errorCodeName(result.error_code.val) << " " << result.error_code.message);
  if (result.error_code.val == ErrorCode::PREEMPTED) {
    server->setPreempted(result, result.error_code.message);
  } else if (isSuccess(result.error_code)) {
    server->setSucceeded(result, result.error_code.message);
  } else {
    server->setAborted(result, result.error_code.message);
  }
  publishState<Feedback>(server, "IDLE");
}

}  // namespace sixdof_planning
