#pragma once
// The simulator's controllers: sixdof_core's trajectory and gripper controllers driving World joints before every
// physics step, hosted for the controllers' ROS interface (sixdof_control's controller_actions.h), which the driver
// node shares. The gripper's trajectory and gripper_cmd controllers drive the same finger: the latest goal wins.
// Single-threaded, as the node: goals arrive between physics steps.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sixdof_control/controller_host.h"
#include "sixdof_control/controller_params.h"
#include "sixdof_sim/controllers.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

// The World's joints as the controllers' configuration reads them.
std::vector<sixdof_control::RobotJoint> robotJoints(const World& world);

class SimControllers : public sixdof_control::ControllerHost {
 public:
  // Every controller of the setup holds the joints where they are. Mimic joints of a trajectory controller are
  // left to the World to drive (their goals' values are checked by the ROS interface). Throws
  // std::invalid_argument when the gripper's joint is a mimic joint. `clock`: the node's time now (s).
  SimControllers(const sixdof_control::ControllerSetup& setup, World& world, std::function<double()> clock);

  // One control step at `now`, before a physics step.
  void update(double now);
  // The world was reset: every goal ends canceled, the controllers hold the current positions.
  void reset();

  TrajectoryResult setGoal(const std::string& controller, const TrajectoryGoal& goal,
                           sixdof_control::GoalCallback done) override;
  void cancel(const std::string& controller) override;
  GripperResult setGripperGoal(const std::string& gripper, const GripperGoal& goal,
                               sixdof_control::GripperCallback done) override;
  void cancelGripper(const std::string& gripper) override;
  bool commands(const std::string& controller) const override;
  std::optional<TrajectorySample> sample(const std::string& controller, double time) const override;
  std::optional<TrajectoryUpdate> lastUpdate(const std::string& controller) const override;
  sixdof_control::GripperReading gripperReading(const std::string& gripper) const override;

 private:
  struct Trajectory {
    TrajectoryController controller;
    std::vector<int> world_index;        // per controller joint
    std::vector<std::string> commanded;  // non-mimic joints: the World drives the mimics
    sixdof_control::GoalCallback done;   // of the active goal
    std::optional<TrajectoryUpdate> last;
  };
  struct Gripper {
    GripperController controller;
    std::size_t world_index;
    sixdof_control::GripperCallback done;
  };
  // Who commands a joint: a trajectory controller's index, or -1 - a gripper's.
  using Owner = int;

  int trajectoryIndex(const std::string& name) const;  // -1 if unknown
  int gripperIndex(const std::string& name) const;     // -1 if unknown
  bool ownsAny(const Trajectory& t, Owner owner) const;
  bool owns(Owner owner, const std::string& joint) const;
  // `owner` commands `joints` from now on; the controllers that commanded any of them end their goals.
  void claim(Owner owner, const std::vector<std::string>& joints);
  void actual(const Trajectory& t, std::vector<double>* q, std::vector<double>* v) const;
  void endTrajectory(Trajectory& t, GoalState state, const TrajectoryResult& result);
  void endGripper(Gripper& g, GoalState state, const std::string& message, bool reached_goal = false,
                  bool stalled = false);

  World& world_;
  std::function<double()> clock_;
  std::vector<Trajectory> trajectories_;
  std::vector<Gripper> grippers_;
  std::map<std::string, Owner> owner_;
};

}  // namespace sixdof_sim
