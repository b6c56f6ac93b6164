#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/cartesian_path.h"
#include "sixdof_core/collision.h"
#include "sixdof_core/ik_solver.h"
#include "sixdof_core/kinematics.h"
#include "sixdof_core/planning.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_core {

// Path constraints (MoveIt's path_constraints): every state of a planned path or Cartesian path satisfies them.
struct PathConstraints {
  // Joints of the group kept inside [lower, upper] (intersected with their limits; a continuous joint becomes
  // bounded when the range is shorter than a full turn). `continuous` is ignored.
  std::vector<JointBounds> joint_bounds;
  // A condition on the whole robot state (e.g. a link's point inside a region); empty = none. Must be thread-safe.
  std::function<bool(const RobotState&)> state;
  // Why `state` rejects a robot state (for error messages); optional.
  std::function<std::string(const RobotState&)> explain;
};

// Options of IK-sampled goals (pose and position goals).
struct PoseGoalOptions {
  IkOptions ik;        // per IK call; ik.seed and ik.random_seed are set per sample
  int max_states = 8;  // see SampledGoal
  int max_calls = 32;
};

// Glue between one planning group of a RobotModel, a CollisionScene and the group's IK solver on one side and
// the callback-based planners (plan(), computeCartesianPath()) on the other. The joints outside the group
// (e.g. the fingers) stay where the start state has them.
//
// Holds shared pointers to immutable parts only; the scene must not be modified while a plan runs.
class PlanningContext {
 public:
  // scene must have been built from model->collisionGeometry() (links are matched by name). ik is the group's
  // solver (its chain must have the group's active joints, in order) and may be null: pose and position goals
  // and Cartesian paths then fail with kInvalidRequest. Throws std::invalid_argument on an unknown group,
  // a scene link unknown to the model, or an IK chain that does not match the group.
  PlanningContext(RobotModelConstPtr model, std::shared_ptr<const CollisionScene> scene, const std::string& group,
                  std::shared_ptr<const IkSolver> ik);

  // Every later plan and Cartesian path keeps to these constraints: the planner samples only inside the joint
  // bounds, IK goal samples outside them are discarded, and states violating `state` are invalid. Throws
  // std::invalid_argument naming a joint that is not an active joint of the group or a range that is empty or
  // outside the joint's limits.
  void setPathConstraints(const PathConstraints& constraints);
  // The group values violate the path constraints (reference supplies the other joints): why, else "".
  std::string pathConstraintViolation(const RobotState& reference, const Eigen::VectorXd& values) const;

  const std::string& group() const { return group_; }
  const std::vector<JointBounds>& joints() const { return joints_; }
  const RobotModel& model() const { return *model_; }

  // State validity of group values with the other joints taken from reference: collision-free in the scene.
  // Thread-safe (each call works on its own copy of the state).
  JointValidityFn validityFn(const RobotState& reference) const;
  // "link3 collides with box, ..." (every colliding pair) explaining an invalid state.
  JointValidityExplainFn explainFn(const RobotState& reference) const;
  // The pre-check of motions from group values q along a joint step (other joints from reference): the scene's
  // sphere proof (CollisionScene::precheckMotion) with each link's motion bounded from the step (lever arms
  // measured at q, growing by what the joints between move). It proves collision-freedom only, not the path
  // constraints' `state`. Thread-safe.
  MotionPrecheckFn precheckFn(const RobotState& reference) const;

  // A problem without a goal: joints, validity callbacks and the pre-check (none under a path constraint's
  // `state`), start = the group's values in start.
  PlanningProblem problem(const RobotState& start, const PlanningOptions& options) const;

  PlanningResult planToJoints(const RobotState& start, const Eigen::VectorXd& goal, double tolerance,
                              const PlanningOptions& options) const;
  // An SRDF group_state of this group; an unknown name is kInvalidRequest naming the known ones.
  PlanningResult planToNamed(const RobotState& start, const std::string& name, double tolerance,
                             const PlanningOptions& options) const;
  // Pose of the group's tip link in the chain base frame, goal states sampled with IK (first seeded with the
  // start, then with random seeds; the closed-form solver's other solutions instead, nearest the start first).
  // pose_goal.ik.position_only makes it a position goal.
  PlanningResult planToPose(const RobotState& start, const Eigen::Isometry3d& tip_pose,
                            const PoseGoalOptions& pose_goal, const PlanningOptions& options) const;
  PlanningResult planToPosition(const RobotState& start, const Eigen::Vector3d& tip_position,
                                const PoseGoalOptions& pose_goal, const PlanningOptions& options) const;

  // Cartesian path of the tip (waypoints in the chain base frame), IK seeded from the previous point.
  CartesianPathResult cartesianPath(const RobotState& start, const std::vector<Eigen::Isometry3d>& waypoints,
                                    double eef_step, const JumpThreshold& jump_threshold, bool avoid_collisions,
                                    const IkOptions& ik_options = IkOptions()) const;

  // World poses of the scene's links for a full robot state (in the scene's link order).
  std::vector<Eigen::Isometry3d> sceneLinkPoses(const RobotState& state) const;
  // The same into *out, reusing its storage.
  void sceneLinkPoses(const RobotState& state, std::vector<Eigen::Isometry3d>* out) const;

 private:
  void computeMotionGains();
  // A copy of this context and of a reference state, shared by the callbacks made from them: they stay valid after
  // this context or the state are gone, and copying a callback copies a pointer.
  struct Bound;
  std::shared_ptr<const Bound> bind(const RobotState& reference) const;
  // validityFn, explainFn and precheckFn of a bound context; the first and last work on the scratch state `scratch`
  // (see planning_context.cpp).
  static JointValidityFn makeValidityFn(std::shared_ptr<const Bound> bound, std::uint64_t scratch);
  static JointValidityExplainFn makeExplainFn(std::shared_ptr<const Bound> bound);
  static MotionPrecheckFn makePrecheckFn(std::shared_ptr<const Bound> bound, std::uint64_t scratch);
  RobotState withGroup(const RobotState& reference, const Eigen::VectorXd& values) const;
  SampledGoal poseSampler(const RobotState& start, const Eigen::Isometry3d& tip_pose, const PoseGoalOptions& pose_goal,
                          const PlanningOptions& options) const;

  RobotModelConstPtr model_;
  std::shared_ptr<const CollisionScene> scene_;
  std::shared_ptr<const IkSolver> ik_;
  std::string group_;
  std::vector<JointBounds> joints_;
  std::vector<bool> prismatic_;
  std::vector<int> variable_indices_;     // RobotState variable index of each group joint
  std::vector<int> scene_link_to_model_;  // model link index of each scene link
  bool constrained_joints_ = false;       // joints_ narrowed by path constraints
  std::function<bool(const RobotState&)> state_constraint_;
  std::function<std::string(const RobotState&)> explain_constraint_;
  // The joints that move a scene link when the group moves, from the link up: the model joint, its child link, the
  // group variable it moves with and by what factor (mimic joints), and the largest distance from its axis to the
  // link's origin over every configuration (the offsets between them). Per scene link.
  struct MotionGain {
    int joint;
    int child_link;
    int variable;
    double factor;
    bool prismatic;
    double lever;
  };
  std::vector<std::vector<MotionGain>> motion_gains_;
};

}  // namespace sixdof_core
