#pragma once
// A controller's joints as controllers.yaml names them, and the mimic joints among them (URDF <mimic>: value =
// multiplier * master + offset). A goal must give a mimic joint its master's value; hardware moves only the actuated
// joints, so the driver maps goals to them and samples back to every joint. ROS-free.

#include <string>
#include <vector>

#include "sixdof_core/control/trajectory_controller.h"

namespace sixdof_control {

// A moving joint of the robot as the controllers need it: its URDF limits and mimic relation.
struct RobotJoint {
  std::string name;
  bool bounded = true;  // false: continuous (no position limit)
  double lower = 0.0;
  double upper = 0.0;
  double max_effort = 0.0;  // URDF <limit effort>
  std::string mimic_of;     // empty: not a mimic joint
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;
};

class ControllerJoints {
 public:
  // Throws std::invalid_argument naming the controller and joint when a joint is not one of `robot`, or mimics a
  // joint the controller does not contain.
  ControllerJoints(const std::string& controller, const std::vector<std::string>& joints,
                   const std::vector<RobotJoint>& robot);

  const std::vector<std::string>& joints() const { return joints_; }
  // The joints that are not mimic joints, in the controller's order.
  const std::vector<std::string>& actuated() const { return actuated_; }
  bool hasMimics() const { return !mimics_.empty(); }

  // Empty when every point gives each mimic joint its master's value (to 1e-6), else the problem (point, joints,
  // the expected and the given value). A goal that leaves out a joint, or a point of the wrong size, passes: the
  // controller's own validation refuses it.
  std::string checkMimics(const sixdof_core::TrajectoryGoal& goal) const;
  // The goal without its mimic joints (points and tolerances), for a controller of the actuated joints. A goal that
  // leaves out a mimic joint of the controller is refused (kInvalidJoints), as a controller of every joint would.
  sixdof_core::TrajectoryResult actuatedGoal(const sixdof_core::TrajectoryGoal& goal,
                                             sixdof_core::TrajectoryGoal& actuated) const;
  // A config of the actuated joints (limits and tolerances of the mimic joints dropped).
  sixdof_core::TrajectoryControllerConfig actuatedConfig(const sixdof_core::TrajectoryControllerConfig& config) const;
  // A sample of the actuated joints extended to every joint: a mimic joint's position is multiplier * master +
  // offset, velocity and acceleration multiplier * master's. With offsets false (errors), the offset is left out.
  sixdof_core::TrajectorySample expand(const sixdof_core::TrajectorySample& actuated, bool offsets = true) const;

 private:
  struct Mimic {
    std::size_t joint;   // index in joints_
    std::size_t master;  // index in joints_
    double multiplier;
    double offset;
  };

  std::string controller_;
  std::vector<std::string> joints_;
  std::vector<std::string> actuated_;
  std::vector<int> actuated_index_;  // per joint: its index in actuated_, -1 for a mimic joint
  std::vector<Mimic> mimics_;
};

}  // namespace sixdof_control
