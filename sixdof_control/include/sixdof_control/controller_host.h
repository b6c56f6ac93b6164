#pragma once
// What the controllers' ROS glue (controller_actions.h) serves: something that runs sixdof_core's trajectory and
// gripper controllers on joints. The simulator's node hosts them on its World's joints, the driver node on the
// control loop (ControlLoop, through a hardware plugin). ROS-free.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "sixdof_core/control/gripper_controller.h"
#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_control {

// How a goal ended. result: kSuccessful when it succeeded, else the error code and a message naming the cause
// (a tolerance, a limit, the fault, the e-stop, a cancel or a preempting goal).
struct GoalOutcome {
  std::string controller;
  sixdof_core::GoalState state = sixdof_core::GoalState::kIdle;  // kSucceeded, kAborted or kCanceled
  sixdof_core::TrajectoryResult result;
};
// Called once per accepted goal, when it ends: on the host's thread, or on the thread of the call that ended it
// (cancel, a preempting goal, e-stop), possibly before the call that set the goal has returned; never with a host
// lock held.
using GoalCallback = std::function<void(const GoalOutcome&)>;

// How a gripper goal ended (GripperCommand's result): kSucceeded (reached, or stalled with allow_stalling), kAborted
// or kCanceled, and why.
struct GripperOutcome {
  std::string controller;
  sixdof_core::GoalState state = sixdof_core::GoalState::kIdle;
  std::string message;
  bool reached_goal = false;
  bool stalled = false;
};
using GripperCallback = std::function<void(const GripperOutcome&)>;

// A gripper joint's reading for GripperCommand's feedback and result.
struct GripperReading {
  double position = 0.0;
  double effort = 0.0;  // 0 where the joint's effort is not measured
};

// The index in `entries` of the entry whose `controller` is configured under `name`, or -1: how a host finds the
// controller a call names.
template <class Entries>
int indexOfController(const Entries& entries, const std::string& name) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].controller.config().name == name) return static_cast<int>(i);
  }
  return -1;
}

// Controllers by name; every time is the host's clock in seconds, which is the node's ROS time. The controllers a
// goal is for name their joints as the controllers config does, mimic joints included (a host whose joints do not
// include them maps them to their masters). Calls may come from any thread.
class ControllerHost {
 public:
  virtual ~ControllerHost() = default;

  // Validates and starts a trajectory goal on the controller (ending its active goal as kCanceled, and the goals of
  // other controllers commanding the same joints). Refused with the controller's error code and a message naming
  // why; `done` is then never called.
  virtual sixdof_core::TrajectoryResult setGoal(const std::string& controller, const sixdof_core::TrajectoryGoal& goal,
                                                GoalCallback done) = 0;
  // Ends the controller's active goal as kCanceled ("canceled"); it holds where its joints are.
  virtual void cancel(const std::string& controller) = 0;
  // The same for a gripper (gripper_cmd) controller.
  virtual sixdof_core::GripperResult setGripperGoal(const std::string& gripper, const sixdof_core::GripperGoal& goal,
                                                    GripperCallback done) = 0;
  virtual void cancelGripper(const std::string& gripper) = 0;

  // Whether the controller commands its joints now (not while another controller's goal has taken them).
  virtual bool commands(const std::string& controller) const = 0;
  // The commanded trajectory at `time` (query_state); nullopt before the controller holds anything.
  virtual std::optional<sixdof_core::TrajectorySample> sample(const std::string& controller, double time) const = 0;
  // The controller's last update (desired and error: feedback and the state topic); nullopt before the first.
  virtual std::optional<sixdof_core::TrajectoryUpdate> lastUpdate(const std::string& controller) const = 0;
  virtual GripperReading gripperReading(const std::string& gripper) const = 0;
};

}  // namespace sixdof_control
