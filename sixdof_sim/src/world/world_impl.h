#pragma once
// The Bullet world's private state (World::Impl), shared by the world_*.cpp sources:
//   world.cpp          construction, build() as named steps, reset, stepping, state
//   world_robot.cpp    the robot: fixed-link merging, the multibody, colliders, servos and limits, mimic gears
//   world_joints.cpp   joint and link readings, joint commands
//   world_objects.cpp  shapes, the ground, object validation, spawning and the object API
//   world_contacts.cpp contacts of a step, the grasp fix's attach/detach and its API

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyFixedConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>

#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/urdf_loader.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {

// Collision margin of every shape: small, so resting contacts are within ~1 mm of the true surface.
inline constexpr double kMargin = 0.001;
// Friction of robot links without <gazebo><mu1> (Gazebo's default mu is 1).
inline constexpr double kDefaultLinkFriction = 1.0;
// Objects at rest (below these speeds for 2 s) sleep until something touches them: resting objects
// then cost no solver time, and sit exactly still.
inline constexpr double kSleepLinearVelocity = 0.005;
inline constexpr double kSleepAngularVelocity = 0.02;
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
  std::vector<std::string> links;                                   // links[0] is the head link
  std::vector<std::string> shape_links;                             // URDF link of each compound child
};

struct LinkRef {
  int body = 0;                                                      // index into bodies
  Eigen::Isometry3d body_to_link = Eigen::Isometry3d::Identity();    // link frame in the body frame
};

struct JointRuntime {
  int body = 0;  // child body (bullet_link = body's bullet link)
  int master = -1;  // joint index of the mimic master, -1 if none
  JointControlMode mode = JointControlMode::kPosition;
  double target_position = 0.0;
  double target_velocity = 0.0;
  double max_effort = 0.0;  // servo bound in force units
  double effort = 0.0;      // kEffort command
  double applied_effort = 0.0;
  btMultiBodyJointMotor* servo = nullptr;
  // Coulomb friction motor: in the world only while the joint is in kEffort mode (see applyCommands).
  std::unique_ptr<btMultiBodyJointMotor> friction;
  bool friction_in_world = false;
};

struct ObjectRuntime {
  ObjectSpec spec;
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> body;
  Eigen::Isometry3d frame_to_body = Eigen::Isometry3d::Identity();  // centre of mass frame in the object frame
};


struct World::Impl {
  WorldOptions options;
  WorldSpec spec;
  sixdof_core::PackageResolver resolver;  // from options.package_search_roots
  std::shared_ptr<const sixdof_core::RobotModel> model;  // the URDF's one model; robot is read from it
  RobotDescription robot;

  // A mesh object's file (robot link meshes come resolved by the model); std::invalid_argument naming the URI.
  std::string meshFile(const Shape& shape) const;

  // Bullet, rebuilt from scratch by build() (construction and reset()).
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  std::unique_ptr<btMultiBody> multibody;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btCollisionShape>> robot_shapes;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> robot_constraints;
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
  std::vector<JointRuntime> joints;
  std::map<std::string, int> joint_index;
  std::vector<double> initial_positions;
  std::vector<btTransform> body_world;  // current world transform of each body frame

  // Time and grasp fix.
  std::uint64_t steps = 0;
  std::function<void(double)> pre_step;
  std::optional<GraspFixConfig> grasp_config;
  std::unique_ptr<GraspFix> grasp_fix;
  bool grasp_enabled = false;
  std::vector<GraspEvent> grasp_events;
  std::vector<Contact> last_contacts;

  btAlignedObjectArray<btQuaternion> scratch_rot;
  btAlignedObjectArray<btVector3> scratch_pos;

  void buildStructure();
  void build();  // every step below, in order: construction and reset()
  void createDynamicsWorld();
  void buildMultibody();
  void addRobotColliders();
  void addJointConstraints();
  void addMimicConstraints();
  void addEnvironment();
  void destroy();
  std::unique_ptr<btCollisionShape> makeShape(const Shape& shape, Eigen::Vector3d* centre);
  Result addObject(const ObjectSpec& spec);
  ObjectRuntime* findObject(const std::string& name) const;
  void refreshKinematics();
  Eigen::Isometry3d objectPose(const ObjectRuntime& object) const;
  Twist objectTwist(const ObjectRuntime& object) const;
  bool linkWorldPose(const std::string& link, Eigen::Isometry3d* pose) const;
  void applyCommands();
  void collectContacts(std::vector<GraspContact>* grasp_contacts);
  void attach(const std::string& object);
  void detach(const std::string& object);
  void pushEvent(GraspEvent::Type type, const std::string& object);
  Result checkJointCommand(const std::string& joint, int* index);
  double dt() const { return options.time_step; }
};

}  // namespace sixdof_sim
