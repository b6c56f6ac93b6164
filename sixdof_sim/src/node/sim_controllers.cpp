#include "sim_controllers.h"

#include <ros/console.h>

#include <algorithm>
#include <stdexcept>

namespace sixdof_sim {

namespace {

// The entry of `entries` whose controller is named `name`, while it has a goal (a `done` callback); else nullptr.
template <class Entry>
Entry* withGoal(std::vector<Entry>& entries, const std::string& name) {
  const int index = sixdof_control::indexOfController(entries, name);
  if (index < 0 || !entries[static_cast<std::size_t>(index)].done) return nullptr;
  return &entries[static_cast<std::size_t>(index)];
}

}  // namespace

using sixdof_control::GoalOutcome;
using sixdof_control::GripperOutcome;

std::vector<sixdof_control::RobotJoint> robotJoints(const World& world) {
  std::vector<sixdof_control::RobotJoint> joints;
  for (const JointInfo& j : world.joints()) {
    joints.push_back(
        {j.name, j.bounded, j.lower, j.upper, j.max_effort, j.mimic_of, j.mimic_multiplier, j.mimic_offset});
  }
  return joints;
}

SimControllers::SimControllers(const sixdof_control::ControllerSetup& setup, World& world,
                               std::function<double()> clock)
    : world_(world), clock_(std::move(clock)) {
  for (const sixdof_control::TrajectoryControllerSetup& c : setup.trajectory) {
    Trajectory t{TrajectoryController(c.config), {}, c.joints.actuated(), nullptr, std::nullopt};
    for (const std::string& j : c.config.joints) t.world_index.push_back(world_.jointIndex(j));
    trajectories_.push_back(std::move(t));
    std::vector<double> q, v;
    actual(trajectories_.back(), &q, &v);
    trajectories_.back().controller.hold(q);
    claim(static_cast<Owner>(trajectories_.size() - 1), trajectories_.back().commanded);
  }
  if (setup.gripper) {
    const GripperControllerConfig& config = *setup.gripper;
    const int w = world_.jointIndex(config.joint);
    if (w < 0) {
      throw std::invalid_argument("gripper_cmd of '" + config.name + "': joint '" + config.joint +
                                  "' is not in the robot");
    }
    const std::string& master = world_.joints()[static_cast<std::size_t>(w)].mimic_of;
    if (!master.empty()) {
      throw std::invalid_argument("gripper_cmd of '" + config.name + "': joint '" + config.joint +
                                  "' is a mimic joint; command its master '" + master + "'");
    }
    grippers_.push_back(Gripper{GripperController(config), static_cast<std::size_t>(w), nullptr});
  }
}

void SimControllers::actual(const Trajectory& t, std::vector<double>* q, std::vector<double>* v) const {
  const std::vector<double> positions = world_.jointPositions();
  const std::vector<double> velocities = world_.jointVelocities();
  q->clear();
  v->clear();
  for (int w : t.world_index) {
    q->push_back(positions[static_cast<std::size_t>(w)]);
    v->push_back(velocities[static_cast<std::size_t>(w)]);
  }
}

int SimControllers::trajectoryIndex(const std::string& name) const {
  return sixdof_control::indexOfController(trajectories_, name);
}

int SimControllers::gripperIndex(const std::string& name) const {
  return sixdof_control::indexOfController(grippers_, name);
}

bool SimControllers::owns(Owner owner, const std::string& joint) const {
  const auto it = owner_.find(joint);
  return it != owner_.end() && it->second == owner;
}

bool SimControllers::ownsAny(const Trajectory& t, Owner owner) const {
  return std::any_of(t.commanded.begin(), t.commanded.end(), [&](const std::string& j) { return owns(owner, j); });
}

void SimControllers::claim(Owner owner, const std::vector<std::string>& joints) {
  std::vector<Owner> released;
  for (const std::string& j : joints) {
    const auto it = owner_.find(j);
    if (it != owner_.end() && it->second != owner &&
        std::find(released.begin(), released.end(), it->second) == released.end()) {
      released.push_back(it->second);
    }
    owner_[j] = owner;
  }
  const std::string why = "preempted by another controller's goal";
  for (Owner r : released) {
    if (r >= 0) {
      Trajectory& t = trajectories_[static_cast<std::size_t>(r)];
      std::vector<double> q, v;
      actual(t, &q, &v);
      t.controller.cancel(q);
      endTrajectory(t, GoalState::kCanceled, TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, why));
    } else {
      Gripper& g = grippers_[static_cast<std::size_t>(-1 - r)];
      g.controller.cancel(world_.jointPositions()[g.world_index]);
      endGripper(g, GoalState::kCanceled, why);
    }
  }
}

void SimControllers::endTrajectory(Trajectory& t, GoalState state, const TrajectoryResult& result) {
  if (!t.done) return;
  const sixdof_control::GoalCallback done = std::move(t.done);
  t.done = nullptr;
  done(GoalOutcome{t.controller.config().name, state, result});
}

void SimControllers::endGripper(Gripper& g, GoalState state, const std::string& message, bool reached_goal,
                                bool stalled) {
  if (!g.done) return;
  const sixdof_control::GripperCallback done = std::move(g.done);
  g.done = nullptr;
  done(GripperOutcome{g.controller.config().name, state, message, reached_goal, stalled});
}

TrajectoryResult SimControllers::setGoal(const std::string& controller, const TrajectoryGoal& goal,
                                         sixdof_control::GoalCallback done) {
  const Owner self = trajectoryIndex(controller);
  if (self < 0) {
    return TrajectoryResult::failure(TrajectoryErrorCode::kInvalidGoal, "unknown controller '" + controller + "'");
  }
  Trajectory& t = trajectories_[static_cast<std::size_t>(self)];
  const double now = clock_();
  TrajectoryResult check = t.controller.validate(goal, now);
  if (!check.ok()) return check;
  if (!ownsAny(t, self)) {
    // Take the joints back from the other controller and start from where they are now.
    claim(self, t.commanded);
    std::vector<double> q, v;
    actual(t, &q, &v);
    t.controller.hold(q);
  }
  check = t.controller.setGoal(goal, now);
  if (!check.ok()) return check;
  endTrajectory(t, GoalState::kCanceled,
                TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "preempted by a new goal"));
  t.done = std::move(done);
  return check;
}

void SimControllers::cancel(const std::string& controller) {
  Trajectory* t = withGoal(trajectories_, controller);
  if (t == nullptr) return;
  std::vector<double> q, v;
  actual(*t, &q, &v);
  t->controller.cancel(q);
  endTrajectory(*t, GoalState::kCanceled, TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "canceled"));
}

GripperResult SimControllers::setGripperGoal(const std::string& gripper, const GripperGoal& goal,
                                             sixdof_control::GripperCallback done) {
  const int index = gripperIndex(gripper);
  if (index < 0) {
    return GripperResult::failure(sixdof_core::GripperStatus::kRefused, "unknown gripper '" + gripper + "'");
  }
  Gripper& g = grippers_[static_cast<std::size_t>(index)];
  const GripperResult check = g.controller.validate(goal);
  if (!check.ok()) return check;
  claim(-1 - index, {g.controller.config().joint});
  g.controller.setGoal(goal, clock_());
  // The fingers start from the contacts of the bodies' present poses (World::refreshContacts).
  world_.refreshContacts(g.controller.config().joint);
  endGripper(g, GoalState::kCanceled, "preempted by a new goal");
  g.done = std::move(done);
  return check;
}

void SimControllers::cancelGripper(const std::string& gripper) {
  Gripper* g = withGoal(grippers_, gripper);
  if (g == nullptr) return;
  g->controller.cancel(world_.jointPositions()[g->world_index]);
  endGripper(*g, GoalState::kCanceled, "canceled");
}

void SimControllers::reset() {
  for (Trajectory& t : trajectories_) {
    std::vector<double> q, v;
    actual(t, &q, &v);
    t.controller.hold(q);
    endTrajectory(t, GoalState::kCanceled,
                  TrajectoryResult::failure(TrajectoryErrorCode::kSuccessful, "canceled by a world reset"));
  }
  for (Gripper& g : grippers_) {
    g.controller.hold(world_.jointPositions()[g.world_index]);
    endGripper(g, GoalState::kCanceled, "canceled by a world reset");
  }
}

void SimControllers::update(double now) {
  for (std::size_t i = 0; i < trajectories_.size(); ++i) {
    Trajectory& t = trajectories_[i];
    const Owner self = static_cast<Owner>(i);
    if (!ownsAny(t, self)) continue;
    std::vector<double> q, v;
    actual(t, &q, &v);
    t.last = t.controller.update(now, q, v);
    const std::vector<std::string>& joints = t.controller.joints();
    for (std::size_t k = 0; k < joints.size(); ++k) {
      if (std::find(t.commanded.begin(), t.commanded.end(), joints[k]) == t.commanded.end() || !owns(self, joints[k])) {
        continue;
      }
      const Result r = world_.setPositionTarget(joints[k], t.last->desired.position[k], t.last->desired.velocity[k]);
      if (!r.ok()) ROS_ERROR_STREAM_THROTTLE(1.0, "[" << t.controller.config().name << "] " << r.message);
    }
    if (t.last->finished) {
      endTrajectory(t, t.last->state == GoalState::kSucceeded ? GoalState::kSucceeded : GoalState::kAborted,
                    t.last->result);
    }
  }
  for (std::size_t i = 0; i < grippers_.size(); ++i) {
    Gripper& g = grippers_[i];
    const std::string& joint = g.controller.config().joint;
    if (!owns(-1 - static_cast<Owner>(i), joint)) continue;
    const GripperUpdate u = g.controller.update(now, world_.jointPositions()[g.world_index]);
    const Result r = world_.setPositionTarget(joint, u.command_position, 0.0, u.command_max_effort);
    if (!r.ok()) ROS_ERROR_STREAM_THROTTLE(1.0, "[" << g.controller.config().name << "/gripper_cmd] " << r.message);
    if (u.finished) {
      const std::string text = u.reached_goal ? "reached the goal"
                               : u.state == GoalState::kSucceeded
                                   ? "stalled (closed on an object): counts as success, allow_stalling is true"
                                   : "stalled before reaching the goal";
      endGripper(g, u.state == GoalState::kSucceeded ? GoalState::kSucceeded : GoalState::kAborted, text,
                 u.reached_goal, u.stalled);
    }
  }
}

bool SimControllers::commands(const std::string& controller) const {
  const int index = trajectoryIndex(controller);
  return index >= 0 && ownsAny(trajectories_[static_cast<std::size_t>(index)], index);
}

std::optional<TrajectorySample> SimControllers::sample(const std::string& controller, double time) const {
  const int index = trajectoryIndex(controller);
  return index < 0 ? std::nullopt : trajectories_[static_cast<std::size_t>(index)].controller.sample(time);
}

std::optional<TrajectoryUpdate> SimControllers::lastUpdate(const std::string& controller) const {
  const int index = trajectoryIndex(controller);
  return index < 0 ? std::nullopt : trajectories_[static_cast<std::size_t>(index)].last;
}

sixdof_control::GripperReading SimControllers::gripperReading(const std::string& gripper) const {
  const int index = gripperIndex(gripper);
  if (index < 0) return {};
  const std::size_t w = grippers_[static_cast<std::size_t>(index)].world_index;
  return {world_.jointPositions()[w], world_.jointEfforts()[w]};
}

}  // namespace sixdof_sim
