#pragma once
// The end of a controller action's goal, shared by the trajectory and gripper action handlers (each keeps the
// goal it is executing as std::optional<GoalHandle>).

#include <optional>
#include <string>

#include <ros/console.h>

namespace sixdof_sim {

// Ends the active goal, if any, as succeeded, canceled or aborted (logged as a warning under `server`), with
// `result` and `text`, and clears it.
template <class GoalHandle, class Result>
void finishGoal(std::optional<GoalHandle>* active, const Result& result, bool succeeded, bool canceled,
                const std::string& server, const std::string& text) {
  if (!*active) return;
  if (succeeded) {
    (*active)->setSucceeded(result, text);
  } else if (canceled) {
    (*active)->setCanceled(result, text);
  } else {
    ROS_WARN_STREAM("[" << server << "] goal aborted: " << text);
    (*active)->setAborted(result, text);
  }
  active->reset();
}

}  // namespace sixdof_sim
