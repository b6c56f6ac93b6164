#pragma once
// The Bullet world: the URDF robot as a fixed-base btMultiBody driven by joint servos, the world
// file's objects as rigid bodies, a fixed-step deterministic stepper and the grasp fix.
// ROS-free; the sixdof_sim node and the controllers sit on top of this API.
//
// Threading: not thread-safe; one thread drives a World (the node serialises its callbacks).

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/robot_model.h"
#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Thrown only by construction on a bad URDF, world spec or options.
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks an object spec (name, finite pose, sizes > 0, mass > 0 unless static, friction >= 0,
// restitution in [0, 1], colour in [0, 1]); the message names the field.
Result validateObjectSpec(const ObjectSpec& spec);

struct WorldOptions {
  double time_step = 0.001;  // s, fixed physics step
  // Bullet constraint solver iterations per step, at most (they stop once converged: most steps take 1-3); a step
  // after a mimic linkage touched an object gets more (kLinkageSqueezeSolverIterations, world_impl.h). 20 keeps every
  // world test passing with margin (they pass with 10 too) at ~1.7x the speed of 50.
  int solver_iterations = 20;
  // Servo position gain (1/s) of kPosition mode: time constant 1/gain. gain * time_step must be <= 1.
  double position_gain = 100.0;
  // Where package://<pkg>/<path> URIs (the URDF's meshes, mesh objects) find <pkg>: each root is a package folder or
  // a folder holding packages a few levels deep, the package named by its package.xml (ROS_PACKAGE_PATH's
  // entries; the core's sixdof_core::PackageResolver).
  std::vector<std::string> package_search_roots;
  // Grasp fix on/off at start (setGraspFixEnabled changes it later). Needs the URDF's
  // gazebo_grasp_fix block or grasp_fix_config; enabling without either throws WorldError.
  bool grasp_fix_enabled = true;
  // The grasp fix of a robot whose URDF has no gazebo_grasp_fix block (e.g. a config package's grasping.yaml,
  // parseGraspingYaml); the URDF's block wins where it has one.
  std::optional<GraspFixConfig> grasp_fix_config;
  // The suction cup of a robot whose URDF has no sixdof_suction block (a grasping.yaml's `suction:`,
  // parseSuctionYaml in sixdof_sim/suction.h); the URDF's block wins where it has one.
  std::optional<SuctionConfig> suction_config;
};

class World {
 public:
  // urdf_xml: the robot_description text. Throws WorldError naming the problem on a bad URDF
  // (unsupported joint types, missing inertials on moving links, unreadable meshes), a bad world
  // spec (duplicate names, non-positive sizes or masses) or bad options.
  World(const std::string& urdf_xml, const WorldSpec& world, const WorldOptions& options = WorldOptions());
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // ---- time ----
  // Advances n fixed steps. Before each step the pre-step callback runs (controllers update there),
  // after each step the grasp fix runs. Same inputs -> bit-identical results.
  void step(std::uint64_t n = 1);
  double simTime() const;           // s since construction / reset()
  std::uint64_t stepCount() const;  // steps since construction / reset()
  double timeStep() const;
  // Called before every physics step with the sim time of the step's start (e.g. controllers).
  void setPreStepCallback(std::function<void(double sim_time)> callback);
  // Back to the initial state: robot at its initial joint positions (all zero, clamped into limits
  // -- see initialJointPositions()), servos holding them, every object of the WorldSpec back at
  // its initial pose (spawned objects removed, deleted ones restored), grasps released,
  // time zero, pending grasp events cleared.
  void reset();

  // ---- robot ----
  // The core model of the URDF (no SRDF), the one the world was built from: the camera renderer and the node
  // read the robot (links, visuals, root link) from it instead of parsing the URDF again.
  const sixdof_core::RobotModel& robotModel() const;
  // The resolver of package:// and file:// URIs built from WorldOptions::package_search_roots: the URDF's meshes
  // and mesh objects resolve with it. A URI it cannot resolve is refused with a message naming the URI.
  const sixdof_core::PackageResolver& packageResolver() const;
  const std::vector<JointInfo>& joints() const;  // actuated joints in URDF order (incl. mimics)
  std::vector<std::string> jointNames() const;
  int jointIndex(const std::string& name) const;  // -1 if unknown
  std::vector<double> initialJointPositions() const;
  std::vector<double> jointPositions() const;
  std::vector<double> jointVelocities() const;
  // Generalised force the joint's actuator applied during the last step (servo or effort command).
  std::vector<double> jointEfforts() const;
  // Teleports joints (resets only): positions set, velocities zeroed, servos switched to hold the
  // new positions. Mimic joints not listed follow their master; listed ones must agree with it.
  // Rejected (nothing changed) on unknown names, NaN, or positions outside the limits.
  Result setJointPositions(const std::vector<std::string>& names, const std::vector<double>& positions);
  // Servo to position (with velocity feed-forward), force bounded by max_effort
  // (0 = the URDF effort limit; above it -> kOutOfLimits). Positions outside the limits -> kOutOfLimits.
  // The mimic joints of `joint` follow automatically.
  Result setPositionTarget(const std::string& joint, double position, double velocity = 0.0, double max_effort = 0.0);
  // Servo to a velocity, force bounded by max_effort (0 = URDF effort limit).
  Result setVelocityTarget(const std::string& joint, double velocity, double max_effort = 0.0);
  // Applies a constant generalised force every step until the next command. |effort| must be
  // <= the URDF effort limit.
  Result setEffort(const std::string& joint, double effort);
  std::optional<JointControlMode> controlMode(const std::string& joint) const;  // nullopt if unknown

  // ---- links ----
  std::vector<std::string> linkNames() const;  // every URDF link, including merged fixed ones
  // World pose of a URDF link frame (tcp and palm too). Status::kUnknownLink if absent.
  Result linkPose(const std::string& link, Eigen::Isometry3d* pose) const;

  // ---- objects ----
  Result spawnObject(const ObjectSpec& spec);
  // Releases it first if grasped. A conveyor's belt cannot be deleted or moved (kInvalidArgument).
  Result deleteObject(const std::string& name);
  std::vector<std::string> objectNames() const;  // spawn order (world-file order first)
  bool hasObject(const std::string& name) const;
  Result objectState(const std::string& name, ObjectState* state) const;
  // Teleports an object (releases it first if grasped). Static objects accept a pose only
  // (a non-zero twist -> kStaticObject).
  Result setObjectState(const std::string& name, const Eigen::Isometry3d& pose, const Twist& twist = Twist());

  // ---- grasp fix ----
  bool graspFixAvailable() const;  // a configuration exists (URDF block or options)
  bool graspFixEnabled() const;
  // Enabling without a configuration -> kInvalidArgument. Disabling releases held objects.
  Result setGraspFixEnabled(bool enabled);
  const std::optional<GraspFixConfig>& graspFixConfig() const;
  // Attach/detach events since the last call (oldest first).
  std::vector<GraspEvent> takeGraspEvents();
  // Objects currently attached by the grasp fix.
  std::vector<std::string> attachedObjects() const;
  // Drops the contact points kept between objects and the bodies `joint` moves (its child body, those of the joints
  // mimicking it and everything they carry): the next step finds them afresh from the bodies' poses. Bullet keeps a
  // contact point, with the normal of the step that found it, for as long as the bodies stay within its breaking
  // threshold; while the grasp fix welds an object to the palm nothing moves them apart, so a normal found at the
  // object's edge as the fingers closed can outlast the grip and hold the fingers shut against their opening
  // effort. The simulator's gripper controller calls this on each new goal. kUnknownJoint for an unknown joint.
  Result refreshContacts(const std::string& joint);

  // ---- conveyors, sources, sinks (sixdof_sim/conveyor.h) ----
  // Sets a belt's speed (m/s along its direction; 0 stops it) and wakes the objects. kUnknownObject for an unknown
  // conveyor, kInvalidArgument for a speed that is not finite. reset() restores the world file's speeds.
  Result setConveyorSpeed(const std::string& conveyor, double speed);
  std::vector<ConveyorState> conveyorStates() const;  // WorldSpec order
  std::vector<SourceState> sourceStates() const;
  std::vector<SinkState> sinkStates() const;
  // Objects deleted by sinks since the last call (oldest first), as "<sink>:<object>".
  std::vector<std::string> takeSunkObjects();

  // ---- suction cup (sixdof_sim/suction.h) ----
  bool suctionAvailable() const;  // a configuration exists (URDF block or options)
  const std::optional<SuctionConfig>& suctionConfig() const;
  // Vacuum on: the cup holds the first object whose surface it touches (the rules in suction.h); off: releases
  // it. kInvalidArgument without a suction configuration.
  Result setVacuum(bool on);
  bool vacuum() const;
  std::string suctionHeld() const;  // the object the cup holds, empty if none
  // The object the cup touches but refused as over max_payload while the vacuum is on, empty if none.
  std::string suctionRefused() const;

  // ---- inspection ----
  std::vector<Contact> contacts() const;  // contact points of the last step (of bodies still in the world)
  WorldState state() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixdof_sim
