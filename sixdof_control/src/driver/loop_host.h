#pragma once
// The driver's controllers: the control loop's (ControlLoop on a hardware plugin), hosted for the controllers' ROS
// interface (controller_actions.h). The loop knows the hardware's actuated joints only and runs on its own steady
// clock: goals are mapped to the actuated joints (a mimic joint's values checked, then dropped) and their times
// from ROS time to the loop's clock; samples and updates come back on every joint of the controller.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sixdof_control/control_loop.h"
#include "sixdof_control/controller_host.h"
#include "sixdof_control/controller_params.h"

namespace sixdof_control {

// The control loop's configuration of the setup's controllers on the hardware's joints: each controller on its
// actuated joints, the gripper on its joint.
void addControllers(const ControllerSetup& setup, ControlLoopConfig& config);

class LoopHost : public ControllerHost {
 public:
  // ros_now: ROS time now (s). The loop runs the setup's controllers (addControllers) and outlives the host.
  LoopHost(ControlLoop& loop, const ControllerSetup& setup, const std::vector<std::string>& hardware_joints,
           std::function<double()> ros_now);

  // ROS time minus the loop's clock, now.
  double offset() const;

  sixdof_core::TrajectoryResult setGoal(const std::string& controller, const sixdof_core::TrajectoryGoal& goal,
                                        GoalCallback done) override;
  void cancel(const std::string& controller) override;
  sixdof_core::GripperResult setGripperGoal(const std::string& gripper, const sixdof_core::GripperGoal& goal,
                                            GripperCallback done) override;
  void cancelGripper(const std::string& gripper) override;
  bool commands(const std::string& controller) const override;
  std::optional<sixdof_core::TrajectorySample> sample(const std::string& controller, double time) const override;
  std::optional<sixdof_core::TrajectoryUpdate> lastUpdate(const std::string& controller) const override;
  GripperReading gripperReading(const std::string& gripper) const override;

 private:
  const ControllerJoints* joints(const std::string& controller) const;

  ControlLoop& loop_;
  std::map<std::string, ControllerJoints> joints_;
  std::map<std::string, std::size_t> gripper_joint_;  // gripper -> index of its joint in the hardware's
  std::function<double()> ros_now_;
};

}  // namespace sixdof_control
