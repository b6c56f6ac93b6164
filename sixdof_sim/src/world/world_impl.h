#pragma once
// The Bullet world's private state (World::Impl), shared by the world_*.cpp sources:
//   world.cpp          construction, build() as named steps, reset, stepping, state
//   world_robot.cpp    the robot: fixed-link merging, the multibody, colliders, servos and limits
//   world_mimic.cpp    mimic joints: gears in the solver, the exact coupling after it
//   world_joints.cpp   joint and link readings, joint commands
//   world_objects.cpp  shapes, the ground, object validation, spawning and the object API
//   world_contacts.cpp contacts of a step, the grasp fix's attach/detach and its API
//   world_conveyors.cpp conveyor belts (surface velocity), sources and sinks
//   suction.cpp        the suction cup: seal test, attach/release, its configuration

#include <BulletCollision/BroadphaseCollision/btAxisSweep3.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyFixedConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/urdf_loader.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

// Collision margin of every shape: small, so resting contacts are within ~1 mm of the true surface.
inline constexpr double kMargin = 0.001;
// Friction of robot links without <gazebo><mu1> (Gazebo's default mu is 1).
inline constexpr double kDefaultLinkFriction = 1.0;
// Objects at rest (below these speeds for 2 s) sleep until something comes near them: resting objects
// then cost no collision or solver time, and sit exactly still. Bullet puts a simulation island to sleep
// only when every body in it rests, and joins bodies whose broadphase bounds overlap into one island:
// hence the exact bounds of the sweep-and-prune broadphase below (the default dynamic tree pads every
// bound by 5 cm, which kept objects up to ~20 cm apart, or near the moving arm, awake forever).
inline constexpr double kSleepLinearVelocity = 0.005;
inline constexpr double kSleepAngularVelocity = 0.02;
// Sweep-and-prune broadphase: its bounds (m; 32-bit quantization, ~0.5 um) and how many collision objects
// (robot links, objects, ground) a world can hold; spawning beyond that is refused.
inline constexpr double kBroadphaseHalfExtent = 1000.0;
inline constexpr int kMaxCollisionObjects = 4096;
// The constraint solver stops iterating once the squared impulse change of an iteration is below this
// (PyBullet's default); solver_iterations stays the bound.
inline constexpr double kSolverResidualThreshold = 1e-7;
// The bound on solver iterations, instead of solver_iterations, for a step after one in which a link that a mimic
// linkage moves touched a dynamic object (linkageSolverIterations). Squeezing an object the grasp fix does not hold
// takes more: the jaw gripper on an upright 3 cm cylinder converges in 25 a step; stopped at 20, 30 or 50, its
// unconverged friction wedged the cylinder into the ground (test_fixture_grippers, test/ros any_gripper). While the
// grasp fix holds an object the squeeze converged at no bound tried (a residual of 0.28 after 200, 8-15 after 20;
// the cause is not established): 50 keeps the adaptive gripper's 6 cm cylinder, which dropped at 20
// (test_fixture_grippers).
inline constexpr int kLinkageSqueezeSolverIterations = 200;
inline constexpr int kLinkageHoldSolverIterations = 50;
// The robot's joint servos and limits start each step's solve from the impulses of the step before (scaled by
// this), so the solver mostly converges in one or two iterations instead of ten to twenty; the mimic gears too
// (started from zero, the squeezed adaptive gripper of test_fixture_grippers chattered at +-10 rad/s and its
// gripper controller never saw the close end).
// Off while the grasp fix holds an object: Bullet then warm-starts the multibody side of the fixed
// constraint but not the object's, which would press the held object's last impulse onto the arm again.
inline constexpr double kArticulatedWarmstartingFactor = 1.0;
// Mimic coupling: position error correction per step and force bound (N or N m; far above any
// joint effort limit so the coupling does not give).
inline constexpr double kGearErp = 0.2;
inline constexpr double kGearMaxForce = 1000.0;
// Impulse bound of the grasp fix's fixed constraint (N s per step): far above what holding an object needs.
inline constexpr double kGraspConstraintMaxImpulse = 50.0;

inline btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
inline Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

inline btTransform toBt(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), toBt(t.translation()));
}

inline Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const btQuaternion q = t.getRotation();
  out.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  out.translation() = toEigen(t.getOrigin());
  return out;
}

inline btQuaternion toBtQuat(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

// ODE/Gazebo combine two friction coefficients with min(); Bullet's default is the product.
inline btScalar combineFrictionMin(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getFriction(), b->getFriction());
}

inline bool finite(const Eigen::Isometry3d& t) { return t.matrix().allFinite(); }

inline std::string describe(const std::string& name) { return "object '" + name + "'"; }

// What a Bullet collision object is, stored in its user index.
enum BodyKind { kRobotBody = 1, kObjectBody = 2, kGroundBody = 3 };

// A group of URDF links rigidly connected by fixed joints: one Bullet body.
struct RobotBody {
  int bullet_link = -1;  // -1: the multibody base
  double mass = 0.0;
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();
  Eigen::Isometry3d head_to_body = Eigen::Isometry3d::Identity();  // Bullet body frame in the head link frame
  std::vector<std::string> links;                                  // links[0] is the head link
  std::vector<std::string> shape_links;                            // URDF link of each compound child
};

struct LinkRef {
  int body = 0;                                                    // index into bodies
  Eigen::Isometry3d body_to_link = Eigen::Isometry3d::Identity();  // link frame in the body frame
};

struct JointRuntime {
  int body = 0;     // child body (bullet_link = body's bullet link)
  int master = -1;  // joint index of the mimic master, -1 if none
  JointControlMode mode = JointControlMode::kPosition;
  double target_position = 0.0;
  double target_velocity = 0.0;
  double max_effort = 0.0;  // servo bound in force units
  double effort = 0.0;      // kEffort command
  double applied_effort = 0.0;
  double linkage_bound = 0.0;   // a master's servo bound: its own and its mimic joints' beside it (applyCommands)
  bool drives_linkage = false;  // a mimic joint's master (applyCommands)
  // A linkage drive's ramped setpoint towards its last command (NaN: not ramping; rampLinkage).
  double ramp_command = std::numeric_limits<double>::quiet_NaN();
  double ramp_setpoint = std::numeric_limits<double>::quiet_NaN();
  btMultiBodyJointMotor* servo = nullptr;  // none on a mimic joint
  // Coulomb friction motor: in the world only while the joint is in kEffort mode (see applyCommands).
  std::unique_ptr<btMultiBodyJointMotor> friction;
  bool friction_in_world = false;
};

// Broadphase filter: the collision group/mask test, and no pair of two robot links (the multibody has no
// self-collision, so such pairs would only be found, kept and skipped again every step).
struct RobotPairFilter : btOverlapFilterCallback {
  bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override;
};

// Bullet's multibody world, except that sleeping rigid bodies are not integrated ahead: Bullet predicts the
// pose of every non-static body each step, asleep or not, although a sleeping body has no velocity and its
// prediction is its pose (a tenth of a step with 100 resting objects). The prediction of an awake body and of
// the robot is Bullet's own.
class DynamicsWorld : public btMultiBodyDynamicsWorld {
 public:
  using btMultiBodyDynamicsWorld::btMultiBodyDynamicsWorld;
  void predictUnconstraintMotion(btScalar time_step) override;
  // Runs before_solve between collision detection and the solver (the conveyor belts' contact motion).
  void solveConstraints(btContactSolverInfo& solver_info) override;
  std::function<void()> before_solve;
  // Runs after the solver, before the positions are integrated (the mimic joints' exact coupling).
  std::function<void()> after_solve;
};

struct ObjectRuntime {
  ObjectSpec spec;
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> body;
  Eigen::Isometry3d frame_to_body = Eigen::Isometry3d::Identity();  // centre of mass frame in the object frame
  int conveyor = -1;  // index into WorldSpec::conveyors when this is a conveyor's belt
};

// A source's schedule and random choices (world_conveyors.cpp).
struct SourceRuntime {
  std::mt19937_64 rng;
  double next_spawn = 0.0;  // s of simulated time
  long long spawned = 0;
};

// The suction cup's state (suction.cpp).
struct SuctionRuntime {
  bool vacuum = false;
  std::string held;
  std::string refused;
  std::unique_ptr<btMultiBodyFixedConstraint> constraint;
};

// A mimic joint's coupling to its master: q = multiplier * q_master + offset (Bullet link and velocity indices).
struct MimicRow {
  int link = 0;
  int master_link = 0;
  int dof = 0;
  int master_dof = 0;
  double multiplier = 1.0;
  double offset = 0.0;
};

// A mimic master's URDF limits, held by the exact coupling too (Bullet link and velocity indices).
struct MimicLimit {
  int link = 0;
  int dof = 0;
  double lower = 0.0;
  double upper = 0.0;
  double reached = 0.0;  // the limit the step would pass (projectMimicMotion)
};

struct World::Impl {
  WorldOptions options;
  WorldSpec spec;
  sixdof_core::PackageResolver resolver;                 // from options.package_search_roots
  std::shared_ptr<const sixdof_core::RobotModel> model;  // the URDF's one model; robot is read from it
  RobotDescription robot;

  // A mesh object's file (robot link meshes come resolved by the model); std::invalid_argument naming the URI.
  std::string meshFile(const Shape& shape) const;

  // Bullet, rebuilt from scratch by build() (construction and reset()).
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  RobotPairFilter robot_pair_filter;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  std::unique_ptr<btMultiBody> multibody;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btCollisionShape>> robot_shapes;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> robot_constraints;
  // The exact mimic coupling (world_mimic.cpp): its rows, and storage kept from step to step.
  std::vector<MimicRow> mimic_rows;
  std::vector<MimicLimit> mimic_limits;  // the bounded masters
  std::vector<btScalar> mimic_unit;      // a row's generalized impulse
  Eigen::MatrixXd mimic_response;        // velocity change of every dof per unit impulse of each row and limit
  std::vector<int> mimic_active;         // the columns of mimic_response solved for: rows, then limits reached
  Eigen::MatrixXd mimic_matrix;          // J M^-1 J^T
  Eigen::VectorXd mimic_rhs, mimic_impulse, mimic_delta, mimic_linkage_delta;
  std::vector<int> mimic_dofs;       // velocity indices of the masters and mimic joints
  std::vector<char> linkage_bodies;  // per body: moved by a mimic joint or its master (linkageSolverIterations)
  Eigen::LDLT<Eigen::MatrixXd> mimic_solver;
  btAlignedObjectArray<btScalar> mimic_scratch_r;
  btAlignedObjectArray<btVector3> mimic_scratch_v;
  std::unique_ptr<btCollisionShape> ground_shape;
  std::unique_ptr<btRigidBody> ground;
  std::vector<std::unique_ptr<ObjectRuntime>> objects;  // spawn order
  std::unique_ptr<btMultiBodyFixedConstraint> grasp_constraint;

  // Robot structure (fixed after construction).
  std::vector<RobotBody> bodies;
  std::map<std::string, LinkRef> links;
  std::vector<std::string> link_order;
  std::vector<JointInfo> joint_infos;
  std::vector<int> joint_description_index;  // into robot.joints
  std::vector<int> joint_parent_body;        // index into bodies of each joint's parent link
  std::vector<JointRuntime> joints;
  std::map<std::string, int> joint_index;
  std::vector<double> initial_positions;
  // World transform of each body frame (bodyWorld()), computed when first needed after a step or teleport.
  mutable std::vector<btTransform> body_world;
  mutable bool body_world_current = false;

  // Time and grasp fix.
  std::uint64_t steps = 0;
  std::function<void(double)> pre_step;
  std::optional<GraspFixConfig> grasp_config;
  std::unique_ptr<GraspFix> grasp_fix;
  bool grasp_enabled = false;
  std::vector<GraspEvent> grasp_events;
  std::vector<GraspContact> grasp_contacts;  // of the last step; reused, so stepping allocates nothing
  std::vector<int> grasp_contact_points;     // contact points behind each of grasp_contacts

  // Conveyors, sources and sinks (world_conveyors.cpp); the suction cup (suction.cpp).
  std::vector<double> conveyor_speeds;
  std::vector<SourceRuntime> sources;
  std::vector<long long> sink_counts;
  std::vector<std::string> sunk;
  std::optional<SuctionConfig> suction_config;
  SuctionRuntime suction;

  mutable btAlignedObjectArray<btQuaternion> scratch_rot;
  mutable btAlignedObjectArray<btVector3> scratch_pos;

  void buildStructure();
  void build();  // every step below, in order: construction and reset()
  void createDynamicsWorld();
  void buildMultibody();
  void addRobotColliders();
  void addJointConstraints();
  void addMimicConstraints();
  void projectMimicMotion();            // after the solver: every mimic joint exactly at its share of its master
  void solveMimicRows();                // projectMimicMotion's impulses for the active rows
  int linkageSolverIterations() const;  // the next step's bound from the last step's manifolds (see above)
  void addEnvironment();
  void destroy();
  std::unique_ptr<btCollisionShape> makeShape(const Shape& shape, Eigen::Vector3d* centre);
  Result addObject(const ObjectSpec& spec);
  ObjectRuntime* findObject(const std::string& name) const;
  void removeObject(ObjectRuntime* object);      // releases it first if held; wakes the other objects
  void refreshKinematics();                      // after teleporting joints: the colliders follow the links
  const btTransform& bodyWorld(int body) const;  // a body frame in the world (forward kinematics once a step)
  Eigen::Isometry3d objectPose(const ObjectRuntime& object) const;
  Twist objectTwist(const ObjectRuntime& object) const;
  bool linkWorldPose(const std::string& link, Eigen::Isometry3d* pose) const;
  void applyCommands();
  void rampLinkage(JointRuntime& runtime, double max_velocity, double q, double* position, double* velocity) const;
  void readAppliedEfforts();  // after a step: each joint's applied_effort
  void collectGraspContacts();
  std::string shapeName(const btCollisionObject* object, int shape_index) const;
  void wakeObjects();
  void attach(const std::string& object);
  void detach(const std::string& object);
  void pushEvent(GraspEvent::Type type, const std::string& object);
  void setArticulatedWarmstarting(bool on);
  void addConveyors();
  void applyBeltMotion();
  Eigen::Vector3d beltVelocity(size_t conveyor) const;
  void stepSources();
  void stepSinks();
  void configureSuction(const std::string& urdf_xml);  // the URDF block, else options; WorldError on a bad one
  void pushSuctionEvent(GraspEvent::Type type);
  void stepSuction();
  void releaseSuction();
  void setCupContacts(ObjectRuntime* object, bool on);  // contacts between the cup's body and the object
  Result checkJointCommand(const std::string& joint, int* index);
  void markBodiesBelow(std::vector<char>* marked) const;  // per body: also every body below a marked one
  double dt() const { return options.time_step; }
};

}  // namespace sixdof_sim
