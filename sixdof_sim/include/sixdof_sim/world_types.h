#pragma once
// Plain data types of the simulated world (no Bullet, no ROS). All poses are in the world frame
// (= base_link), SI units, angles in radians.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "sixdof_core/geometry.h"
#include "sixdof_core/result.h"

namespace sixdof_sim {

// Outcome of a World call that can fail on bad input. message names the problem (empty on success).
enum class Status {
  kOk = 0,
  kUnknownJoint,
  kUnknownLink,
  kUnknownObject,
  kAlreadyExists,
  kInvalidArgument,  // NaN, wrong sizes, negative mass/size, bad mesh, ...
  kOutOfLimits,      // position outside the URDF limits, effort above the URDF effort limit
  kMimicJoint,       // a mimic joint was commanded directly: command its master joint instead
  kStaticObject,     // a twist was given to a static object
};

using Result = sixdof_core::Result<Status>;

enum class JointType { kRevolute, kPrismatic };

// One actuated (revolute, continuous or prismatic) URDF joint, in the core robot model's joint order. Fixed
// joints are merged into their parent link.
struct JointInfo {
  std::string name;
  JointType type = JointType::kRevolute;
  std::string parent_link;
  std::string child_link;
  // Continuous joints follow the core's convention (docs/design.md "One robot model"): bounded = false and
  // lower/upper -pi/pi, a nominal range only; no limit is enforced on them.
  bool bounded = true;
  double lower = 0.0;         // URDF <limit lower>
  double upper = 0.0;         // URDF <limit upper>
  double max_velocity = 0.0;  // URDF <limit velocity>: for controllers; a linkage's master ramps at it
  double max_effort = 0.0;    // URDF <limit effort> (N m or N)
  double damping = 0.0;       // URDF <dynamics damping>: viscous, always applied
  // URDF <dynamics friction> (Coulomb, N m or N): applied in kEffort mode only. Not modelled in the
  // servo modes: a second velocity constraint on a servoed joint fights the servo in Bullet's
  // iterative solver and makes light links jitter.
  double friction = 0.0;
  // Mimic joints (URDF <mimic>): q = multiplier * q_master + offset, enforced by a gear constraint and
  // an exact velocity coupling after the solver (a parallel gripper stays symmetric when an object pushes
  // one finger); no servo of their own: the master's drives the linkage, bounded by its own effort limit
  // plus theirs for mimic joints beside it. They cannot be commanded directly (Status::kMimicJoint).
  std::string mimic_of;  // empty: not a mimic joint
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;

  bool withinLimits(double position) const { return !bounded || (position >= lower && position <= upper); }
};

// How a joint is currently driven.
//  kPosition: an implicit servo (Bullet joint motor): velocity target
//             v* = velocity_ff + position_gain * (position - q), force bounded by max_effort.
//  kVelocity: the same servo with position_gain = 0.
//  kEffort:   a constant generalised force applied every step (no servo).
enum class JointControlMode { kPosition, kVelocity, kEffort };

// The shape value type is the core's (sixdof_core/geometry.h): one Shape for the robot model, the planning
// scene and the simulator. Objects give mesh_resource (a path or package:// URI); the world resolves it.
using ShapeType = sixdof_core::ShapeType;
using Shape = sixdof_core::Shape;

struct Color {
  double r = 0.7, g = 0.7, b = 0.7, a = 1.0;
};

// An object of the world (a world-file entry, or spawned at run time).
struct ObjectSpec {
  std::string name;
  Shape shape;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // initial pose of the shape's centre
  double mass = 0.1;                                       // kg; must be > 0 unless is_static
  bool is_static = false;                                  // static: immovable (tables, walls)
  bool collision = true;                                   // false: a visual-only marker
  double friction = 0.8;                                   // Coulomb coefficient
  double restitution = 0.0;
  Color color;
  bool table = false;  // declared under the world file's tables: (a support surface)
  std::string bin;     // the bin this object is a wall of; empty: none
};

struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m/s, world frame, of the shape's centre
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s, world frame
};

struct ObjectState {
  ObjectSpec spec;  // spec.pose is the current pose
  Twist twist;
  std::string attached_to;  // link holding it through the grasp fix, empty if none
};

struct GroundPlane {
  bool enabled = true;
  double z = 0.0;  // height of the plane (the floor, below the table)
  double friction = 0.8;
  double restitution = 0.0;
};

// A simulated RGB-D camera (world file `cameras:`; rendered by CameraRenderer, sixdof_sim/camera.h).
struct CameraSpec {
  std::string name;         // topics <name>/..., tf frames <name>_link and <name>_optical_frame
  std::string parent_link;  // robot link the camera is mounted on; empty: fixed in the world frame
  // The camera link frame (REP 103 body frame: x forward, y left, z up) in the parent frame.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int width = 640;                   // pixels
  int height = 480;                  // pixels
  double horizontal_fov = 1.0471975511965976;  // rad (60 deg), in (0, pi)
  double rate = 15.0;                // frames per second of simulated time
  double near_clip = 0.05;           // m: depth is NaN outside [near_clip, far_clip]
  double far_clip = 5.0;             // m
  double depth_noise_stddev = 0.0;   // m, Gaussian, added to every valid depth
  // 1/m: the noise's standard deviation grows by this times depth^2 (stereo and structured-light sensors).
  double depth_noise_quadratic = 0.0;
  std::uint64_t seed = 0;            // of the depth noise
};

// A whole world: what a world file describes (see worlds/README.md).
// A bin of the world file's bins: section, its defaults applied. Its walls are objects of WorldSpec::objects
// (ObjectSpec::bin names the bin).
struct BinSpec {
  std::string name;
  Color color;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centre of the bottom
  double yaw = 0.0;                                    // rad, about z
  Eigen::Vector2d size = Eigen::Vector2d::Zero();      // outer footprint
  double wall_height = 0.03;
  double wall_thickness = 0.01;
};

// A conveyor (world file `conveyors:`): a static box whose top face is a moving belt. The belt moves what rests on
// it through a surface velocity: its contacts with objects get friction directions along and across the belt and a
// target slip of `speed` along it (Bullet's contact motion), so objects are carried by friction, never moved by the
// simulator. The box is also an object of the world (static, named `name`), published like a table.
struct ConveyorSpec {
  std::string name;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();          // full extents: x along the conveyor, y across, z thick
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the box centre; the belt is its top face (+z)
  double speed = 0.0;                                      // m/s along direction; 0 stops it, < 0 runs backwards
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();    // unit vector in the belt plane, conveyor frame (x, y)
  double friction = 0.8;                                   // Coulomb coefficient of the belt
  Color color{0.2, 0.2, 0.2, 1.0};
};

// Where a source spawns: shapes, sizes, colours and timing (world file `sources:`).
struct SourceSpec {
  std::string name;      // spawned objects are named <name>_<n>, n = 1, 2, ...
  std::string conveyor;  // the conveyor the objects are put on
  // On the belt's top face, in the conveyor frame from its centre (m); each spawn adds a uniform offset across the
  // belt (conveyor y) in [-lateral_jitter, lateral_jitter].
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double lateral_jitter = 0.0;
  std::vector<ShapeType> shapes{ShapeType::kBox};  // box: a cube of edge `size`; cylinder: diameter and height
                                                   // `size`, upright; sphere: diameter `size`
  double min_size = 0.03;                          // m: each object's size is uniform in [min_size, max_size]
  double max_size = 0.06;
  std::vector<Color> colors;  // each object's colour is one of these (uniform); empty: the default grey
  double mass = 0.05;         // kg
  double friction = 0.8;
  // Timing in simulated time: the first spawn at `start`, then every `period` s (period > 0), or after intervals
  // uniform in [min_interval, max_interval] (period = 0).
  double start = 0.0;
  double period = 0.0;
  double min_interval = 0.0;
  double max_interval = 0.0;
  std::uint64_t seed = 0;  // of the choices (shape, size, colour, jitter, intervals)
  long long max_count = 0;  // stop after this many spawns; 0: no limit
};

// A sink (world file `sinks:`): deletes every dynamic object whose origin is inside its box region, or below a
// height, and counts them. Objects held by the grasp fix or the suction cup are not taken.
struct SinkSpec {
  std::string name;
  bool below_only = false;                                 // true: the region is z < below (no box)
  double below = 0.0;                                      // m
  Eigen::Vector3d size = Eigen::Vector3d::Zero();          // box region: full extents
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // box region: its centre
};

struct WorldSpec {
  std::string name;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  GroundPlane ground;
  std::vector<ObjectSpec> objects;  // tables are static boxes; markers have collision = false
  std::vector<BinSpec> bins;
  std::vector<CameraSpec> cameras;
  std::vector<ConveyorSpec> conveyors;  // their belts are objects too, made by the World
  std::vector<SourceSpec> sources;
  std::vector<SinkSpec> sinks;
};

// Grasp-fix configuration: the URDF's <gazebo><plugin name="gazebo_grasp_fix"><arm> block.
struct GraspFixConfig {
  std::string arm_name;
  std::string palm_link;
  std::vector<std::string> gripper_links;
  double forces_angle_tolerance = 100.0;  // degrees, >= 90
  double update_rate = 4.0;               // Hz of SIMULATED time
  int grip_count_threshold = 4;
  int max_grip_count = 8;
  double release_tolerance = 0.005;  // m
  bool disable_collisions_on_attach = false;
};

struct GraspEvent {
  enum class Type { kAttached, kDetached };
  Type type = Type::kAttached;
  double sim_time = 0.0;
  std::string arm;
  std::string object;
  std::string palm_link;
  std::vector<std::string> gripper_links;
};

// The suction cup (a config package's grasping.yaml `suction:` or the URDF's <gazebo><plugin name="sixdof_suction">
// block; sixdof_sim/suction.h). The cup's face is the plane through the cup link's origin, its outward normal the
// link's +z axis.
struct SuctionConfig {
  std::string arm_name;
  std::string cup_link;
  double max_payload = 0.5;        // kg: heavier objects are refused (they stay where they are)
  double tilt_tolerance = 0.2;     // rad: largest angle between the cup's axis and the object's surface normal
  double contact_distance = 0.003;  // m: the object's surface within this of the cup's face counts as touching
  std::string controller = "gripper_controller";  // the node serves <controller>/gripper_cmd for the vacuum
};

// The state of the conveyors, sources and sinks (World::conveyorStates and friends).
struct ConveyorState {
  std::string name;
  double speed = 0.0;                                  // m/s
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // the belt surface's velocity in the world frame
};

struct SourceState {
  std::string name;
  long long spawned = 0;  // since construction / reset()
};

struct SinkState {
  std::string name;
  long long deleted = 0;  // since construction / reset()
};

// A robot/object contact point of the last step (for debugging, contact topics and tests).
struct Contact {
  std::string body_a;  // robot link name or object name; "ground" for the ground plane
  std::string body_b;
  bool a_is_robot = false;
  bool b_is_robot = false;
  Eigen::Vector3d position_on_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_on_b = Eigen::Vector3d::Zero();  // world frame, pointing from b to a
  double depth = 0.0;                                     // negative when penetrating
  double normal_impulse = 0.0;                            // N s over the last step
};

// The complete dynamic state, for determinism checks and snapshots. Vectors follow joints() and
// objectNames() order.
struct WorldState {
  double sim_time = 0.0;
  std::vector<double> joint_positions;
  std::vector<double> joint_velocities;
  std::vector<Eigen::Isometry3d> object_poses;
  std::vector<Twist> object_twists;
};

}  // namespace sixdof_sim
