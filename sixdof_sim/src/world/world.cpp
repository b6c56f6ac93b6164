#include "sixdof_sim/world.h"

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

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "mesh_loader.h"
#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/urdf_loader.h"

namespace sixdof_sim {
namespace {

// Collision margin of every shape: small, so resting contacts are within ~1 mm of the true surface.
constexpr double kMargin = 0.001;
// Friction of robot links without <gazebo><mu1> (Gazebo's default mu is 1).
constexpr double kDefaultLinkFriction = 1.0;
// Objects at rest (below these speeds for 2 s) sleep until something touches them: resting objects
// then cost no solver time, and sit exactly still.
constexpr double kSleepLinearVelocity = 0.005;
constexpr double kSleepAngularVelocity = 0.02;
// Mimic coupling: position error correction per step and force bound (N or N m; far above any
// joint effort limit so the coupling does not give).
constexpr double kGearErp = 0.2;
constexpr double kGearMaxForce = 1000.0;
// Impulse bound of the grasp fix's fixed constraint (N s per step): far above what holding an object needs.
constexpr double kGraspConstraintMaxImpulse = 50.0;

btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

btTransform toBt(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), toBt(t.translation()));
}

Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const btQuaternion q = t.getRotation();
  out.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  out.translation() = toEigen(t.getOrigin());
  return out;
}

btQuaternion toBtQuat(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return btQuaternion(q.x(), q.y(), q.z(), q.w());
}

// ODE/Gazebo combine two friction coefficients with min(); Bullet's default is the product.
btScalar combineFrictionMin(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getFriction(), b->getFriction());
}

bool finite(const Eigen::Isometry3d& t) { return t.matrix().allFinite(); }

std::string describe(const std::string& name) { return "object '" + name + "'"; }

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

}  // namespace

Result validateObjectSpec(const ObjectSpec& spec) {
  auto bad = [&](const std::string& what) {
    return Result{Status::kInvalidArgument, describe(spec.name) + ": " + what};
  };
  if (spec.name.empty()) return {Status::kInvalidArgument, "object name must not be empty"};
  if (!finite(spec.pose)) return bad("pose is not finite");
  const Shape& s = spec.shape;
  switch (s.type) {
    case ShapeType::kBox:
      if (!(s.box_size.minCoeff() > 0.0) || !s.box_size.allFinite()) return bad("box size must be > 0 in x, y and z");
      break;
    case ShapeType::kCylinder:
      if (!(s.radius > 0.0 && s.length > 0.0) || !std::isfinite(s.radius) || !std::isfinite(s.length)) {
        return bad("cylinder radius and length must be > 0");
      }
      break;
    case ShapeType::kSphere:
      if (!(s.radius > 0.0) || !std::isfinite(s.radius)) return bad("sphere radius must be > 0");
      break;
    case ShapeType::kMesh:
      if (s.mesh_resource.empty()) return bad("mesh resource is empty");
      if (!(s.mesh_scale.minCoeff() > 0.0) || !s.mesh_scale.allFinite()) return bad("mesh scale must be > 0");
      break;
  }
  if (!spec.is_static && (!(spec.mass > 0.0) || !std::isfinite(spec.mass))) {
    return bad("mass must be > 0 for a dynamic object");
  }
  if (!(spec.friction >= 0.0) || !std::isfinite(spec.friction)) return bad("friction must be >= 0");
  if (!(spec.restitution >= 0.0 && spec.restitution <= 1.0)) return bad("restitution must be in [0, 1]");
  for (double c : {spec.color.r, spec.color.g, spec.color.b, spec.color.a}) {
    if (!(c >= 0.0 && c <= 1.0)) return bad("colour components must be in [0, 1]");
  }
  return Result::success();
}

struct World::Impl {
  WorldOptions options;
  WorldSpec spec;
  RobotDescription robot;
  MeshCache meshes;

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
  void build();
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

// ---------------------------------------------------------------------------------------------
// Robot structure: merge fixed links, principal inertia frames, joint tables.

void World::Impl::buildStructure() {
  std::map<std::string, int> link_to_description;
  for (size_t i = 0; i < robot.links.size(); ++i) link_to_description[robot.links[i].name] = static_cast<int>(i);

  // Per URDF link: its body and its frame in the body's head frame.
  std::map<std::string, std::pair<int, Eigen::Isometry3d>> in_head;
  struct Accum {
    double mass = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia_origin = Eigen::Matrix3d::Zero();  // about the head origin
  };
  std::vector<Accum> accum;
  for (size_t i = 0; i < robot.links.size(); ++i) {
    const RobotLink& link = robot.links[i];
    int body = 0;
    Eigen::Isometry3d head_to_link = Eigen::Isometry3d::Identity();
    if (i == 0 || !robot.joints[i - 1].fixed) {
      body = static_cast<int>(bodies.size());
      bodies.emplace_back();
      accum.emplace_back();
    } else {
      const RobotJoint& joint = robot.joints[i - 1];
      const auto& parent = in_head.at(joint.info.parent_link);
      body = parent.first;
      head_to_link = parent.second * joint.origin;
    }
    in_head[link.name] = {body, head_to_link};
    bodies[body].links.push_back(link.name);
    // Mass properties in the head frame (parallel-axis theorem about the head origin).
    const Eigen::Matrix3d r = head_to_link.linear();
    const Eigen::Vector3d c = head_to_link * link.com;
    const Eigen::Matrix3d i_com = r * link.inertia * r.transpose();
    accum[body].mass += link.mass;
    accum[body].moment += link.mass * c;
    accum[body].inertia_origin +=
        i_com + link.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }

  for (size_t b = 0; b < bodies.size(); ++b) {
    RobotBody& body = bodies[b];
    const Accum& a = accum[b];
    body.mass = a.mass;
    if (a.mass <= 0.0) {
      // Only the fixed base may be massless: it never moves.
      body.principal_inertia = Eigen::Vector3d::Ones();
      continue;
    }
    const Eigen::Vector3d com = a.moment / a.mass;
    const Eigen::Matrix3d i_com =
        a.inertia_origin - a.mass * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d principal = i_com.diagonal();
    const double off_diagonal = std::abs(i_com(0, 1)) + std::abs(i_com(0, 2)) + std::abs(i_com(1, 2));
    if (off_diagonal > 1e-12 * i_com.diagonal().cwiseAbs().maxCoeff()) {
      // Bullet bodies need diagonal inertia: use the principal axes as the body frame.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(i_com);
      rotation = eig.eigenvectors();
      if (rotation.determinant() < 0.0) rotation.col(2) = -rotation.col(2);
      principal = eig.eigenvalues();
    }
    if (b > 0 && !(principal.minCoeff() > 0.0)) {
      throw WorldError("URDF link '" + body.links.front() + "' (with its fixed children) has a zero principal inertia");
    }
    body.principal_inertia = principal.cwiseMax(1e-12);
    body.head_to_body.linear() = rotation;
    body.head_to_body.translation() = com;
  }

  for (const RobotLink& link : robot.links) {
    const auto& entry = in_head.at(link.name);
    links[link.name] = {entry.first, bodies[entry.first].head_to_body.inverse() * entry.second};
    link_order.push_back(link.name);
  }
  // Bullet link indices: bodies in order, the base body being -1.
  for (size_t b = 0; b < bodies.size(); ++b) bodies[b].bullet_link = static_cast<int>(b) - 1;

  for (size_t j = 0; j < robot.joints.size(); ++j) {
    const RobotJoint& joint = robot.joints[j];
    if (joint.fixed) continue;
    joint_index[joint.info.name] = static_cast<int>(joint_infos.size());
    joint_infos.push_back(joint.info);
    joint_description_index.push_back(static_cast<int>(j));
    JointRuntime runtime;
    runtime.body = links.at(joint.info.child_link).body;
    joints.push_back(std::move(runtime));
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    if (!joint_infos[j].mimic_of.empty()) joints[j].master = joint_index.at(joint_infos[j].mimic_of);
  }
  // Initial positions: zero, moved into the limits when zero is outside them.
  for (const JointInfo& info : joint_infos) {
    initial_positions.push_back(std::min(std::max(0.0, info.lower), info.upper));
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].master >= 0) {
      const JointInfo& info = joint_infos[j];
      initial_positions[j] = info.mimic_multiplier * initial_positions[joints[j].master] + info.mimic_offset;
    }
  }
}

std::unique_ptr<btCollisionShape> World::Impl::makeShape(const Shape& shape, Eigen::Vector3d* centre) {
  *centre = Eigen::Vector3d::Zero();
  std::unique_ptr<btCollisionShape> out;
  switch (shape.type) {
    case ShapeType::kBox:
      out = std::make_unique<btBoxShape>(toBt(shape.box_size / 2.0));
      break;
    case ShapeType::kCylinder:
      out = std::make_unique<btCylinderShapeZ>(btVector3(shape.radius, shape.radius, shape.length / 2.0));
      break;
    case ShapeType::kSphere:
      out = std::make_unique<btSphereShape>(shape.radius);
      break;
    case ShapeType::kMesh: {
      const std::string path = resolveResource(shape.mesh_resource, options.package_search_roots);
      if (path.empty()) {
        throw std::invalid_argument("mesh '" + shape.mesh_resource + "' not found (package search roots: " +
                                    std::to_string(options.package_search_roots.size()) + ")");
      }
      const std::vector<Eigen::Vector3d>& vertices = meshes.vertices(path);
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300);
      Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1e300);
      for (const Eigen::Vector3d& v : vertices) {
        const Eigen::Vector3d p = v.cwiseProduct(shape.mesh_scale);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      // The hull is centred on its bounding-box centre (the body's centre of mass approximation).
      *centre = (lo + hi) / 2.0;
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Eigen::Vector3d& v : vertices) hull->addPoint(toBt(v.cwiseProduct(shape.mesh_scale) - *centre), false);
      hull->recalcLocalAabb();
      hull->optimizeConvexHull();
      hull->initializePolyhedralFeatures();
      out = std::move(hull);
      break;
    }
  }
  out->setMargin(kMargin);
  return out;
}

void World::Impl::build() {
  collision_config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(collision_config.get());
  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<btMultiBodyConstraintSolver>();
  world = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(),
                                                     collision_config.get());
  world->setGravity(toBt(spec.gravity));
  btContactSolverInfo& info = world->getSolverInfo();
  info.m_numIterations = options.solver_iterations;
  info.m_timeStep = options.time_step;
  // Contacts: penetration deeper than 0.5 mm is corrected by split impulse (position only, no
  // velocity: objects are not launched); shallower by velocity (ERP 0.2: at most 0.1 m/s).
  // Deterministic order (no randomisation), warm starting for stable resting contacts.
  info.m_erp = 0.2;
  info.m_erp2 = 0.2;
  info.m_globalCfm = 0.0;
  info.m_splitImpulse = 1;
  info.m_splitImpulsePenetrationThreshold = -0.0005;
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_USE_2_FRICTION_DIRECTIONS;
  gCalculateCombinedFrictionCallback = &combineFrictionMin;

  // ---- robot ----
  const int num_links = static_cast<int>(bodies.size()) - 1;
  const RobotBody& base = bodies[0];
  multibody = std::make_unique<btMultiBody>(num_links, base.mass > 0.0 ? base.mass : 1.0, toBt(base.principal_inertia),
                                            true, false);
  std::map<std::string, Eigen::Isometry3d> parent_link_in_head;
  for (const auto& entry : links) {
    const RobotBody& body = bodies[entry.second.body];
    parent_link_in_head[entry.first] = body.head_to_body * entry.second.body_to_link;
  }
  for (size_t b = 1; b < bodies.size(); ++b) {
    const RobotBody& body = bodies[b];
    // The joint whose child is this body's head link.
    const RobotJoint* joint = nullptr;
    for (const RobotJoint& candidate : robot.joints) {
      if (candidate.info.child_link == body.links.front()) joint = &candidate;
    }
    const LinkRef& parent_ref = links.at(joint->info.parent_link);
    const RobotBody& parent = bodies[parent_ref.body];
    // Child head frame (at q = 0) in the parent body's head frame.
    const Eigen::Isometry3d parent_head_to_child_head = parent_link_in_head.at(joint->info.parent_link) * joint->origin;
    const Eigen::Isometry3d parent_body_to_child_head = parent.head_to_body.inverse() * parent_head_to_child_head;
    const Eigen::Matrix3d parent_body_to_child_body = parent_body_to_child_head.linear() * body.head_to_body.linear();
    const btQuaternion rot_parent_to_this = toBtQuat(parent_body_to_child_body.transpose());
    const btVector3 axis = toBt(body.head_to_body.linear().transpose() * joint->axis);
    const btVector3 parent_com_to_pivot = toBt(parent_body_to_child_head.translation());
    const btVector3 pivot_to_com = toBt(body.head_to_body.linear().transpose() * body.head_to_body.translation());
    const int parent_link = parent.bullet_link;
    if (joint->info.type == JointType::kRevolute) {
      multibody->setupRevolute(body.bullet_link, body.mass, toBt(body.principal_inertia), parent_link,
                               rot_parent_to_this, axis, parent_com_to_pivot, pivot_to_com, true);
    } else {
      multibody->setupPrismatic(body.bullet_link, body.mass, toBt(body.principal_inertia), parent_link,
                                rot_parent_to_this, axis, parent_com_to_pivot, pivot_to_com, true);
    }
  }
  multibody->setBaseWorldTransform(toBt(base.head_to_body));
  multibody->finalizeMultiDof();
  multibody->setHasSelfCollision(false);
  multibody->setLinearDamping(0.0);
  multibody->setAngularDamping(0.0);
  multibody->setUseGyroTerm(true);
  world->addMultiBody(multibody.get());

  // Colliders: one compound per body, a child per URDF collision element.
  for (size_t b = 0; b < bodies.size(); ++b) {
    RobotBody& body = bodies[b];
    auto compound = std::make_unique<btCompoundShape>();
    body.shape_links.clear();
    double friction = kDefaultLinkFriction;
    for (const std::string& link_name : body.links) {
      const RobotLink& link = *std::find_if(robot.links.begin(), robot.links.end(),
                                            [&](const RobotLink& l) { return l.name == link_name; });
      if (link.friction) friction = *link.friction;
      const Eigen::Isometry3d body_to_link = links.at(link_name).body_to_link;
      for (const RobotCollision& collision : link.collisions) {
        Eigen::Vector3d centre;
        std::unique_ptr<btCollisionShape> child;
        try {
          child = makeShape(collision.shape, &centre);
        } catch (const std::invalid_argument& e) {
          throw WorldError("URDF link '" + link_name + "': " + e.what());
        }
        Eigen::Isometry3d local = body_to_link * collision.origin;
        local.translation() += local.linear() * centre;
        compound->addChildShape(toBt(local), child.get());
        body.shape_links.push_back(link_name);
        robot_shapes.push_back(std::move(child));
      }
    }
    if (compound->getNumChildShapes() == 0) continue;
    compound->setMargin(kMargin);
    auto collider = std::make_unique<btMultiBodyLinkCollider>(multibody.get(), body.bullet_link);
    collider->setCollisionShape(compound.get());
    collider->setFriction(friction);
    collider->setRestitution(0.0);
    collider->setUserIndex(kRobotBody);
    collider->setUserIndex2(static_cast<int>(b));
    int group = btBroadphaseProxy::DefaultFilter;
    int mask = btBroadphaseProxy::AllFilter;
    if (body.bullet_link < 0) {
      // The fixed base never needs contacts with static geometry (the table it stands on).
      group = btBroadphaseProxy::StaticFilter;
      mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter;
      collider->setCollisionFlags(collider->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      multibody->setBaseCollider(collider.get());
    } else {
      multibody->getLink(body.bullet_link).m_collider = collider.get();
    }
    world->addCollisionObject(collider.get(), group, mask);
    robot_shapes.push_back(std::move(compound));
    colliders.push_back(std::move(collider));
  }

  // Joint servos, friction, limits.
  for (size_t j = 0; j < joints.size(); ++j) {
    JointRuntime& runtime = joints[j];
    const JointInfo& info = joint_infos[j];
    const int link = bodies[runtime.body].bullet_link;
    runtime.mode = JointControlMode::kPosition;
    runtime.target_position = initial_positions[j];
    runtime.target_velocity = 0.0;
    runtime.max_effort = info.max_effort;
    runtime.effort = 0.0;
    runtime.applied_effort = 0.0;
    auto servo = std::make_unique<btMultiBodyJointMotor>(multibody.get(), link, 0.0, info.max_effort * dt());
    servo->setErp(1.0);
    runtime.servo = servo.get();
    world->addMultiBodyConstraint(servo.get());
    robot_constraints.push_back(std::move(servo));
    runtime.friction.reset();
    runtime.friction_in_world = false;
    if (info.friction > 0.0) {
      // Coulomb joint friction as a zero-velocity motor bounded by the friction force.
      runtime.friction = std::make_unique<btMultiBodyJointMotor>(multibody.get(), link, 0.0, info.friction * dt());
      runtime.friction->setVelocityTarget(0.0, 1.0);
    }
    if (std::isfinite(info.lower) && std::isfinite(info.upper)) {
      auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(multibody.get(), link, info.lower, info.upper);
      world->addMultiBodyConstraint(limit.get());
      robot_constraints.push_back(std::move(limit));
    }
    multibody->setJointPos(link, initial_positions[j]);
    multibody->setJointVel(link, 0.0);
  }
  // Mimic joints: a gear constraint q_mimic - multiplier * q_master = offset couples them rigidly, so a
  // parallel gripper stays symmetric when an object pushes one finger (independent servos alone let a
  // squeezed object and both fingers drift sideways as a unit once both servos saturate).
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].master < 0) continue;
    const JointInfo& info = joint_infos[j];
    const int link = bodies[joints[j].body].bullet_link;
    const int master_link = bodies[joints[joints[j].master].body].bullet_link;
    auto gear = std::make_unique<btMultiBodyGearConstraint>(multibody.get(), link, multibody.get(), master_link,
                                                            btVector3(0, 0, 0), btVector3(0, 0, 0),
                                                            btMatrix3x3::getIdentity(), btMatrix3x3::getIdentity());
    gear->setGearRatio(-info.mimic_multiplier);
    gear->setRelativePositionTarget(info.mimic_offset);
    gear->setErp(kGearErp);
    gear->setMaxAppliedImpulse(kGearMaxForce * dt());
    world->addMultiBodyConstraint(gear.get());
    robot_constraints.push_back(std::move(gear));
  }

  // ---- static environment and objects ----
  if (spec.ground.enabled) {
    ground_shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), spec.ground.z);
    btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, ground_shape.get());
    ground = std::make_unique<btRigidBody>(ci);
    ground->setFriction(spec.ground.friction);
    ground->setRestitution(spec.ground.restitution);
    ground->setUserIndex(kGroundBody);
    world->addRigidBody(ground.get(), btBroadphaseProxy::StaticFilter,
                        btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  }
  for (const ObjectSpec& object : spec.objects) {
    const Result r = addObject(object);
    if (!r.ok()) throw WorldError("world '" + spec.name + "': " + r.message);
  }
  refreshKinematics();
}

void World::Impl::destroy() {
  if (world) {
    if (grasp_constraint) world->removeMultiBodyConstraint(grasp_constraint.get());
    for (auto& c : robot_constraints) world->removeMultiBodyConstraint(c.get());
    for (JointRuntime& j : joints) {
      if (j.friction_in_world) world->removeMultiBodyConstraint(j.friction.get());
      j.friction_in_world = false;
    }
    for (auto& o : objects) world->removeRigidBody(o->body.get());
    if (ground) world->removeRigidBody(ground.get());
    for (auto& c : colliders) world->removeCollisionObject(c.get());
    if (multibody) world->removeMultiBody(multibody.get());
  }
  grasp_constraint.reset();
  robot_constraints.clear();
  for (JointRuntime& j : joints) j.friction.reset();
  objects.clear();
  ground.reset();
  ground_shape.reset();
  colliders.clear();
  robot_shapes.clear();
  multibody.reset();
  world.reset();
  solver.reset();
  broadphase.reset();
  dispatcher.reset();
  collision_config.reset();
}

Result World::Impl::addObject(const ObjectSpec& object_spec) {
  Result valid = validateObjectSpec(object_spec);
  if (!valid.ok()) return valid;
  if (findObject(object_spec.name) != nullptr) {
    return {Status::kAlreadyExists, describe(object_spec.name) + " already exists"};
  }
  auto object = std::make_unique<ObjectRuntime>();
  object->spec = object_spec;
  Eigen::Vector3d centre;
  try {
    object->shape = makeShape(object_spec.shape, &centre);
  } catch (const std::invalid_argument& e) {
    return {Status::kInvalidArgument, describe(object_spec.name) + ": " + e.what()};
  }
  object->frame_to_body.translation() = centre;
  const double mass = object_spec.is_static ? 0.0 : object_spec.mass;
  btVector3 inertia(0, 0, 0);
  if (mass > 0.0) object->shape->calculateLocalInertia(mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, object->shape.get(), inertia);
  ci.m_friction = object_spec.friction;
  ci.m_restitution = object_spec.restitution;
  // Round objects would otherwise roll forever on the slightest tilt or impulse.
  ci.m_rollingFriction = object_spec.shape.type == ShapeType::kBox ? 0.0 : 1e-4;
  ci.m_spinningFriction = 1e-4;
  object->body = std::make_unique<btRigidBody>(ci);
  object->body->setWorldTransform(toBt(object_spec.pose * object->frame_to_body));
  object->body->setSleepingThresholds(kSleepLinearVelocity, kSleepAngularVelocity);
  object->body->setUserIndex(kObjectBody);
  int group = btBroadphaseProxy::DefaultFilter;
  int mask = btBroadphaseProxy::AllFilter;
  if (!object_spec.collision) {
    group = 0;
    mask = 0;
    object->body->setCollisionFlags(object->body->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
  } else if (object_spec.is_static) {
    group = btBroadphaseProxy::StaticFilter;
    mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter;
  }
  world->addRigidBody(object->body.get(), group, mask);
  objects.push_back(std::move(object));
  return Result::success();
}

ObjectRuntime* World::Impl::findObject(const std::string& name) const {
  for (const auto& o : objects) {
    if (o->spec.name == name) return o.get();
  }
  return nullptr;
}

void World::Impl::refreshKinematics() {
  multibody->forwardKinematics(scratch_rot, scratch_pos);
  multibody->updateCollisionObjectWorldTransforms(scratch_rot, scratch_pos);
  body_world.resize(bodies.size());
  for (size_t b = 0; b < bodies.size(); ++b) {
    body_world[b] = btTransform(scratch_rot[b].inverse(), scratch_pos[b]);
  }
}

Eigen::Isometry3d World::Impl::objectPose(const ObjectRuntime& object) const {
  return toEigen(object.body->getWorldTransform()) * object.frame_to_body.inverse();
}

Twist World::Impl::objectTwist(const ObjectRuntime& object) const {
  Twist twist;
  twist.angular = toEigen(object.body->getAngularVelocity());
  const Eigen::Vector3d com = toEigen(object.body->getWorldTransform().getOrigin());
  const Eigen::Vector3d origin = objectPose(object).translation();
  twist.linear = toEigen(object.body->getLinearVelocity()) + twist.angular.cross(origin - com);
  return twist;
}

bool World::Impl::linkWorldPose(const std::string& link, Eigen::Isometry3d* pose) const {
  const auto it = links.find(link);
  if (it == links.end()) return false;
  *pose = toEigen(body_world[it->second.body]) * it->second.body_to_link;
  return true;
}

void World::Impl::applyCommands() {
  for (size_t j = 0; j < joints.size(); ++j) {
    JointRuntime& runtime = joints[j];
    const JointInfo& info = joint_infos[j];
    const JointRuntime& source = runtime.master >= 0 ? joints[runtime.master] : runtime;
    const double scale = runtime.master >= 0 ? info.mimic_multiplier : 1.0;
    const double offset = runtime.master >= 0 ? info.mimic_offset : 0.0;
    const int link = bodies[runtime.body].bullet_link;
    if (runtime.master >= 0) runtime.mode = source.mode;
    switch (runtime.mode) {
      case JointControlMode::kPosition:
      case JointControlMode::kVelocity: {
        const double position = scale * source.target_position + offset;
        const double velocity = scale * source.target_velocity;
        const double gain = runtime.mode == JointControlMode::kPosition ? options.position_gain * dt() : 0.0;
        // A mimic joint is bounded by its own limit unless its master's command lowered the bound.
        const double bound = runtime.master >= 0 ? std::min(info.max_effort, source.max_effort) : runtime.max_effort;
        runtime.servo->setPositionTarget(position, gain);
        runtime.servo->setVelocityTarget(velocity, 1.0);
        runtime.servo->setMaxAppliedImpulse(bound * dt());
        break;
      }
      case JointControlMode::kEffort:
        runtime.servo->setMaxAppliedImpulse(0.0);
        multibody->addJointTorque(link, scale * source.effort);
        break;
    }
    if (info.damping > 0.0) multibody->addJointTorque(link, -info.damping * multibody->getJointVel(link));
    // Coulomb friction acts on an unservoed joint only: a second velocity constraint on a servoed
    // joint fights the servo in the iterative solver and makes the wrist jitter. Out of the world
    // otherwise, so it costs no solver time.
    const bool want_friction = runtime.friction && runtime.mode == JointControlMode::kEffort;
    if (want_friction != runtime.friction_in_world) {
      if (want_friction) {
        world->addMultiBodyConstraint(runtime.friction.get());
      } else {
        world->removeMultiBodyConstraint(runtime.friction.get());
      }
      runtime.friction_in_world = want_friction;
    }
  }
}

void World::Impl::collectContacts(std::vector<GraspContact>* grasp_contacts) {
  last_contacts.clear();
  const int manifolds = dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    const int points = manifold->getNumContacts();
    if (points == 0) continue;
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    auto name_of = [&](const btCollisionObject* o, int shape_index) -> std::string {
      switch (o->getUserIndex()) {
        case kRobotBody: {
          const RobotBody& body = bodies[o->getUserIndex2()];
          if (shape_index >= 0 && shape_index < static_cast<int>(body.shape_links.size())) {
            return body.shape_links[shape_index];
          }
          return body.links.front();
        }
        case kObjectBody:
          for (const auto& obj : objects) {
            if (obj->body.get() == o) return obj->spec.name;
          }
          return "";
        default:
          return "ground";
      }
    };
    const bool a_robot = a->getUserIndex() == kRobotBody;
    const bool b_robot = b->getUserIndex() == kRobotBody;
    // Grasp-fix samples: one per (robot link, dynamic object) pair and step, averaged over points.
    std::map<std::string, GraspContact> pairs;
    std::map<std::string, int> pair_points;
    for (int p = 0; p < points; ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      Contact contact;
      contact.body_a = name_of(a, pt.m_index0);
      contact.body_b = name_of(b, pt.m_index1);
      contact.a_is_robot = a_robot;
      contact.b_is_robot = b_robot;
      contact.position_on_b = toEigen(pt.getPositionWorldOnB());
      contact.normal_on_b = toEigen(pt.m_normalWorldOnB);
      contact.depth = pt.getDistance();
      contact.normal_impulse = pt.getAppliedImpulse();
      last_contacts.push_back(contact);
      if (a_robot == b_robot) continue;
      const btCollisionObject* object = a_robot ? b : a;
      if (object->getUserIndex() != kObjectBody || object->isStaticObject()) continue;
      // Impulse on body A; the object receives it with the sign of its side.
      const btVector3 impulse = pt.m_normalWorldOnB * pt.m_appliedImpulse +
                                pt.m_lateralFrictionDir1 * pt.m_appliedImpulseLateral1 +
                                pt.m_lateralFrictionDir2 * pt.m_appliedImpulseLateral2;
      const Eigen::Vector3d force = toEigen(a_robot ? -impulse : impulse) / dt();
      const std::string link = a_robot ? contact.body_a : contact.body_b;
      const std::string object_name = a_robot ? contact.body_b : contact.body_a;
      const std::string key = object_name + '\n' + link;
      GraspContact& gc = pairs[key];
      gc.object = object_name;
      gc.link = link;
      gc.force_on_object += force;
      gc.point += toEigen((pt.getPositionWorldOnA() + pt.getPositionWorldOnB()) * 0.5);
      ++pair_points[key];
    }
    for (auto& entry : pairs) {
      const int n = pair_points[entry.first];
      entry.second.force_on_object /= n;
      entry.second.point /= n;
      grasp_contacts->push_back(entry.second);
    }
  }
}

void World::Impl::pushEvent(GraspEvent::Type type, const std::string& object) {
  GraspEvent event;
  event.type = type;
  event.sim_time = static_cast<double>(steps) * dt();
  event.arm = grasp_config->arm_name;
  event.object = object;
  event.palm_link = grasp_config->palm_link;
  event.gripper_links = grasp_config->gripper_links;
  grasp_events.push_back(event);
}

void World::Impl::attach(const std::string& name) {
  ObjectRuntime* object = findObject(name);
  const auto palm = links.find(grasp_config->palm_link);
  if (object == nullptr || palm == links.end()) return;
  const int body = palm->second.body;
  // Fix the object at its current pose relative to the palm's body.
  const btTransform body_to_object = body_world[body].inverse() * object->body->getWorldTransform();
  grasp_constraint = std::make_unique<btMultiBodyFixedConstraint>(
      multibody.get(), bodies[body].bullet_link, object->body.get(), body_to_object.getOrigin(), btVector3(0, 0, 0),
      body_to_object.getBasis(), btMatrix3x3::getIdentity());
  grasp_constraint->setMaxAppliedImpulse(kGraspConstraintMaxImpulse);
  grasp_constraint->finalizeMultiDof();
  world->addMultiBodyConstraint(grasp_constraint.get());
  if (grasp_config->disable_collisions_on_attach) {
    object->body->setCollisionFlags(object->body->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
  }
  pushEvent(GraspEvent::Type::kAttached, name);
}

void World::Impl::detach(const std::string& name) {
  if (!grasp_constraint) return;
  world->removeMultiBodyConstraint(grasp_constraint.get());
  grasp_constraint.reset();
  ObjectRuntime* object = findObject(name);
  if (object != nullptr && object->spec.collision) {
    object->body->setCollisionFlags(object->body->getCollisionFlags() & ~btCollisionObject::CF_NO_CONTACT_RESPONSE);
  }
  pushEvent(GraspEvent::Type::kDetached, name);
}

// ---------------------------------------------------------------------------------------------

World::World(const std::string& urdf_xml, const WorldSpec& world, const WorldOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (!(options.time_step > 0.0) || !std::isfinite(options.time_step)) {
    throw WorldError("time_step must be > 0");
  }
  if (options.solver_iterations <= 0) throw WorldError("solver_iterations must be > 0");
  if (!(options.position_gain >= 0.0) || options.position_gain * options.time_step > 1.0) {
    throw WorldError("position_gain must be in [0, 1 / time_step]");
  }
  if (!world.gravity.allFinite()) throw WorldError("gravity is not finite");
  impl_->options = options;
  impl_->spec = world;
  try {
    impl_->robot = parseRobotDescription(urdf_xml);
  } catch (const std::invalid_argument& e) {
    throw WorldError(e.what());
  }
  std::set<std::string> names;
  for (const ObjectSpec& object : world.objects) {
    if (!names.insert(object.name).second) {
      throw WorldError("world '" + world.name + "': duplicate object '" + object.name + "'");
    }
  }
  impl_->buildStructure();
  impl_->grasp_config = options.grasp_fix_config ? options.grasp_fix_config : impl_->robot.grasp_fix;
  if (impl_->grasp_config) {
    const GraspFixConfig& config = *impl_->grasp_config;
    try {
      validateGraspFixConfig(config);
    } catch (const std::invalid_argument& e) {
      throw WorldError(e.what());
    }
    for (const std::string& link : config.gripper_links) {
      if (!impl_->links.count(link)) {
        throw WorldError("gazebo_grasp_fix: gripper_link '" + link + "' is not a URDF link");
      }
    }
    if (!impl_->links.count(config.palm_link)) {
      throw WorldError("gazebo_grasp_fix: palm_link '" + config.palm_link + "' is not a URDF link");
    }
    Impl* impl = impl_.get();
    impl_->grasp_fix = std::make_unique<GraspFix>(
        config, [impl](const std::string& name, Eigen::Isometry3d* pose) { return impl->linkWorldPose(name, pose); },
        [impl](const std::string& name, Eigen::Isometry3d* pose) {
          const ObjectRuntime* object = impl->findObject(name);
          if (object == nullptr) return false;
          *pose = impl->objectPose(*object);
          return true;
        });
  }
  if (options.grasp_fix_enabled && !impl_->grasp_fix) {
    throw WorldError(
        "grasp fix enabled but the URDF has no <gazebo><plugin name=\"gazebo_grasp_fix\"> block and no "
        "grasp_fix_config was given");
  }
  impl_->grasp_enabled = options.grasp_fix_enabled;
  try {
    impl_->build();
  } catch (const std::invalid_argument& e) {
    throw WorldError(e.what());
  }
}

World::~World() { impl_->destroy(); }

void World::step(std::uint64_t n) {
  Impl& d = *impl_;
  std::vector<GraspContact> grasp_contacts;
  for (std::uint64_t i = 0; i < n; ++i) {
    if (d.pre_step) d.pre_step(simTime());
    d.applyCommands();
    // maxSubSteps = 0: exactly one internal step of time_step (no accumulator, no interpolation).
    d.world->stepSimulation(d.dt(), 0, d.dt());
    ++d.steps;
    d.refreshKinematics();
    for (size_t j = 0; j < d.joints.size(); ++j) {
      JointRuntime& runtime = d.joints[j];
      if (runtime.mode != JointControlMode::kEffort) {
        runtime.applied_effort = runtime.servo->getAppliedImpulse(0) / d.dt();
      } else if (runtime.master >= 0) {
        runtime.applied_effort = d.joint_infos[j].mimic_multiplier * d.joints[runtime.master].effort;
      } else {
        runtime.applied_effort = runtime.effort;
      }
    }
    grasp_contacts.clear();
    d.collectContacts(&grasp_contacts);
    if (d.grasp_enabled) {
      const GraspDecision decision = d.grasp_fix->update(simTime(), grasp_contacts);
      for (const std::string& object : decision.detach) d.detach(object);
      for (const std::string& object : decision.attach) d.attach(object);
    }
  }
}

double World::simTime() const { return static_cast<double>(impl_->steps) * impl_->dt(); }
std::uint64_t World::stepCount() const { return impl_->steps; }
double World::timeStep() const { return impl_->dt(); }
void World::setPreStepCallback(std::function<void(double)> callback) { impl_->pre_step = std::move(callback); }

void World::reset() {
  Impl& d = *impl_;
  d.destroy();
  d.steps = 0;
  d.grasp_events.clear();
  d.last_contacts.clear();
  if (d.grasp_fix) d.grasp_fix->reset();
  d.build();
}

const std::vector<JointInfo>& World::joints() const { return impl_->joint_infos; }

std::vector<std::string> World::jointNames() const {
  std::vector<std::string> names;
  for (const JointInfo& info : impl_->joint_infos) names.push_back(info.name);
  return names;
}

int World::jointIndex(const std::string& name) const {
  const auto it = impl_->joint_index.find(name);
  return it == impl_->joint_index.end() ? -1 : it->second;
}

std::vector<double> World::initialJointPositions() const { return impl_->initial_positions; }

std::vector<double> World::jointPositions() const {
  std::vector<double> q;
  for (const JointRuntime& j : impl_->joints) {
    q.push_back(impl_->multibody->getJointPos(impl_->bodies[j.body].bullet_link));
  }
  return q;
}

std::vector<double> World::jointVelocities() const {
  std::vector<double> v;
  for (const JointRuntime& j : impl_->joints) {
    v.push_back(impl_->multibody->getJointVel(impl_->bodies[j.body].bullet_link));
  }
  return v;
}

std::vector<double> World::jointEfforts() const {
  std::vector<double> e;
  for (const JointRuntime& j : impl_->joints) e.push_back(j.applied_effort);
  return e;
}

Result World::setJointPositions(const std::vector<std::string>& names, const std::vector<double>& positions) {
  Impl& d = *impl_;
  if (names.size() != positions.size()) {
    return {Status::kInvalidArgument, "setJointPositions: " + std::to_string(names.size()) + " names but " +
                                          std::to_string(positions.size()) + " positions"};
  }
  std::vector<double> q = jointPositions();
  std::vector<bool> given(q.size(), false);
  for (size_t i = 0; i < names.size(); ++i) {
    const int j = jointIndex(names[i]);
    if (j < 0) return {Status::kUnknownJoint, "unknown joint '" + names[i] + "'"};
    if (!std::isfinite(positions[i])) {
      return {Status::kInvalidArgument, "joint '" + names[i] + "': position is not finite"};
    }
    const JointInfo& info = d.joint_infos[j];
    if (positions[i] < info.lower || positions[i] > info.upper) {
      return {Status::kOutOfLimits, "joint '" + names[i] + "': position " + std::to_string(positions[i]) +
                                        " outside [" + std::to_string(info.lower) + ", " +
                                        std::to_string(info.upper) + "]"};
    }
    q[j] = positions[i];
    given[j] = true;
  }
  for (size_t j = 0; j < q.size(); ++j) {
    const int master = d.joints[j].master;
    if (master < 0) continue;
    const JointInfo& info = d.joint_infos[j];
    const double expected = info.mimic_multiplier * q[master] + info.mimic_offset;
    if (given[j] && std::abs(q[j] - expected) > 1e-6) {
      return {Status::kMimicJoint, "joint '" + info.name + "' mimics '" + info.mimic_of + "': expected " +
                                       std::to_string(expected) + ", got " + std::to_string(q[j])};
    }
    q[j] = expected;
  }
  // An attached object moves with the palm.
  std::optional<btTransform> palm_to_object;
  ObjectRuntime* attached = nullptr;
  int palm_body = 0;
  if (d.grasp_fix && !d.grasp_fix->attached().empty()) {
    attached = d.findObject(d.grasp_fix->attached());
    palm_body = d.links.at(d.grasp_config->palm_link).body;
    if (attached != nullptr) palm_to_object = d.body_world[palm_body].inverse() * attached->body->getWorldTransform();
  }
  for (size_t j = 0; j < q.size(); ++j) {
    JointRuntime& runtime = d.joints[j];
    const int link = d.bodies[runtime.body].bullet_link;
    d.multibody->setJointPos(link, q[j]);
    d.multibody->setJointVel(link, 0.0);
    runtime.mode = JointControlMode::kPosition;
    runtime.target_position = q[j];
    runtime.target_velocity = 0.0;
    runtime.max_effort = d.joint_infos[j].max_effort;
  }
  d.refreshKinematics();
  if (attached != nullptr && palm_to_object) {
    attached->body->setWorldTransform(d.body_world[palm_body] * *palm_to_object);
    attached->body->setLinearVelocity(btVector3(0, 0, 0));
    attached->body->setAngularVelocity(btVector3(0, 0, 0));
  }
  return Result::success();
}

Result World::Impl::checkJointCommand(const std::string& joint, int* index) {
  const auto it = joint_index.find(joint);
  if (it == joint_index.end()) return {Status::kUnknownJoint, "unknown joint '" + joint + "'"};
  *index = it->second;
  if (joints[*index].master >= 0) {
    return {Status::kMimicJoint,
            "joint '" + joint + "' mimics '" + joint_infos[*index].mimic_of + "': command '" +
                joint_infos[*index].mimic_of + "'"};
  }
  return Result::success();
}

namespace {
Result checkEffortBound(const JointInfo& info, double max_effort, double* bound) {
  if (!std::isfinite(max_effort) || max_effort < 0.0) {
    return {Status::kInvalidArgument, "joint '" + info.name + "': max_effort must be >= 0"};
  }
  if (max_effort > info.max_effort) {
    return {Status::kOutOfLimits, "joint '" + info.name + "': max_effort " + std::to_string(max_effort) +
                                      " above the URDF effort limit " + std::to_string(info.max_effort)};
  }
  *bound = max_effort > 0.0 ? max_effort : info.max_effort;
  return Result::success();
}
}  // namespace

Result World::setPositionTarget(const std::string& joint, double position, double velocity, double max_effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  const JointInfo& info = impl_->joint_infos[j];
  if (!std::isfinite(position) || !std::isfinite(velocity)) {
    return {Status::kInvalidArgument, "joint '" + joint + "': target is not finite"};
  }
  if (position < info.lower || position > info.upper) {
    return {Status::kOutOfLimits, "joint '" + joint + "': target " + std::to_string(position) + " outside [" +
                                      std::to_string(info.lower) + ", " + std::to_string(info.upper) + "]"};
  }
  double bound = 0.0;
  r = checkEffortBound(info, max_effort, &bound);
  if (!r.ok()) return r;
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kPosition;
  runtime.target_position = position;
  runtime.target_velocity = velocity;
  runtime.max_effort = bound;
  return Result::success();
}

Result World::setVelocityTarget(const std::string& joint, double velocity, double max_effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  if (!std::isfinite(velocity)) return {Status::kInvalidArgument, "joint '" + joint + "': velocity is not finite"};
  double bound = 0.0;
  r = checkEffortBound(impl_->joint_infos[j], max_effort, &bound);
  if (!r.ok()) return r;
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kVelocity;
  runtime.target_velocity = velocity;
  runtime.max_effort = bound;
  return Result::success();
}

Result World::setEffort(const std::string& joint, double effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  const JointInfo& info = impl_->joint_infos[j];
  if (!std::isfinite(effort)) return {Status::kInvalidArgument, "joint '" + joint + "': effort is not finite"};
  if (std::abs(effort) > info.max_effort) {
    return {Status::kOutOfLimits, "joint '" + joint + "': |effort| " + std::to_string(std::abs(effort)) +
                                      " above the URDF effort limit " + std::to_string(info.max_effort)};
  }
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kEffort;
  runtime.effort = effort;
  return Result::success();
}

std::optional<JointControlMode> World::controlMode(const std::string& joint) const {
  const int j = jointIndex(joint);
  if (j < 0) return std::nullopt;
  const JointRuntime& runtime = impl_->joints[j];
  return runtime.master >= 0 ? impl_->joints[runtime.master].mode : runtime.mode;
}

std::vector<std::string> World::linkNames() const { return impl_->link_order; }

Result World::linkPose(const std::string& link, Eigen::Isometry3d* pose) const {
  if (!impl_->linkWorldPose(link, pose)) return {Status::kUnknownLink, "unknown link '" + link + "'"};
  return Result::success();
}

Result World::spawnObject(const ObjectSpec& spec) { return impl_->addObject(spec); }

Result World::deleteObject(const std::string& name) {
  Impl& d = *impl_;
  ObjectRuntime* object = d.findObject(name);
  if (object == nullptr) return {Status::kUnknownObject, "unknown " + describe(name)};
  if (d.grasp_fix) {
    if (d.grasp_fix->attached() == name) d.detach(name);
    d.grasp_fix->forget(name);
  }
  d.world->removeRigidBody(object->body.get());
  d.objects.erase(std::find_if(d.objects.begin(), d.objects.end(), [&](const auto& o) { return o.get() == object; }));
  return Result::success();
}

std::vector<std::string> World::objectNames() const {
  std::vector<std::string> names;
  for (const auto& o : impl_->objects) names.push_back(o->spec.name);
  return names;
}

bool World::hasObject(const std::string& name) const { return impl_->findObject(name) != nullptr; }

Result World::objectState(const std::string& name, ObjectState* state) const {
  const ObjectRuntime* object = impl_->findObject(name);
  if (object == nullptr) return {Status::kUnknownObject, "unknown " + describe(name)};
  state->spec = object->spec;
  state->spec.pose = impl_->objectPose(*object);
  state->twist = impl_->objectTwist(*object);
  state->attached_to.clear();
  if (impl_->grasp_fix && impl_->grasp_fix->attached() == name) state->attached_to = impl_->grasp_config->palm_link;
  return Result::success();
}

Result World::setObjectState(const std::string& name, const Eigen::Isometry3d& pose, const Twist& twist) {
  Impl& d = *impl_;
  ObjectRuntime* object = d.findObject(name);
  if (object == nullptr) return {Status::kUnknownObject, "unknown " + describe(name)};
  if (!finite(pose) || !twist.linear.allFinite() || !twist.angular.allFinite()) {
    return {Status::kInvalidArgument, describe(name) + ": pose or twist is not finite"};
  }
  if (object->spec.is_static && (!twist.linear.isZero(0.0) || !twist.angular.isZero(0.0))) {
    return {Status::kStaticObject, describe(name) + " is static: it cannot be given a twist"};
  }
  if (d.grasp_fix) {
    if (d.grasp_fix->attached() == name) d.detach(name);
    d.grasp_fix->forget(name);
  }
  object->body->setWorldTransform(toBt(pose * object->frame_to_body));
  const Eigen::Vector3d com = pose * object->frame_to_body.translation();
  object->body->setLinearVelocity(toBt(twist.linear + twist.angular.cross(com - pose.translation())));
  object->body->setAngularVelocity(toBt(twist.angular));
  object->body->clearForces();
  object->body->activate(true);
  // Static bodies have no motion integration: the broadphase must learn the new pose now.
  d.world->updateSingleAabb(object->body.get());
  return Result::success();
}

bool World::graspFixAvailable() const { return impl_->grasp_fix != nullptr; }
bool World::graspFixEnabled() const { return impl_->grasp_enabled; }

Result World::setGraspFixEnabled(bool enabled) {
  Impl& d = *impl_;
  if (enabled && !d.grasp_fix) {
    return {Status::kInvalidArgument, "no grasp-fix configuration (URDF gazebo_grasp_fix block or options)"};
  }
  if (!enabled && d.grasp_fix) {
    if (!d.grasp_fix->attached().empty()) d.detach(d.grasp_fix->attached());
    d.grasp_fix->reset();
  }
  d.grasp_enabled = enabled;
  return Result::success();
}

const std::optional<GraspFixConfig>& World::graspFixConfig() const { return impl_->grasp_config; }

std::vector<GraspEvent> World::takeGraspEvents() {
  std::vector<GraspEvent> events;
  events.swap(impl_->grasp_events);
  return events;
}

std::vector<std::string> World::attachedObjects() const {
  if (!impl_->grasp_fix || impl_->grasp_fix->attached().empty()) return {};
  return {impl_->grasp_fix->attached()};
}

std::vector<Contact> World::contacts() const { return impl_->last_contacts; }

WorldState World::state() const {
  WorldState s;
  s.sim_time = simTime();
  s.joint_positions = jointPositions();
  s.joint_velocities = jointVelocities();
  for (const auto& o : impl_->objects) {
    s.object_poses.push_back(impl_->objectPose(*o));
    s.object_twists.push_back(impl_->objectTwist(*o));
  }
  return s;
}

}  // namespace sixdof_sim
