#include "world_impl.h"

#include "sixdof_core/mesh_loader.h"

namespace sixdof_sim {
namespace {

// The ground: Bullet's infinite plane (the same contacts), but with bounds that end at its surface. The plane's
// own bounds are infinite in every direction, so every moving body overlapped it in the broadphase and was
// tested against it every step, however high above the floor.
class GroundPlaneShape : public btStaticPlaneShape {
 public:
  explicit GroundPlaneShape(double z) : btStaticPlaneShape(btVector3(0, 0, 1), z) {}
  void getAabb(const btTransform& transform, btVector3& aabb_min, btVector3& aabb_max) const override {
    btStaticPlaneShape::getAabb(transform, aabb_min, aabb_max);
    aabb_max.setZ(m_planeConstant);
  }
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

std::string World::Impl::meshFile(const Shape& shape) const {
  if (!shape.mesh_path.empty()) return shape.mesh_path;
  try {
    return resolver.resolve(shape.mesh_resource);
  } catch (const sixdof_core::RobotModelError& e) {
    throw std::invalid_argument(e.what());
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
      const std::string path = meshFile(shape);
      // The core's loader (cached per process, scale applied): the hull needs only the vertices.
      const sixdof_core::MeshLoadResult loaded = sixdof_core::loadMesh(path, shape.mesh_scale);
      if (!loaded) throw std::invalid_argument(loaded.message);
      const std::vector<Eigen::Vector3d>& vertices = loaded.mesh->vertices;
      if (vertices.size() < 4) throw std::invalid_argument("mesh '" + path + "' has fewer than 4 vertices");
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300);
      Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1e300);
      for (const Eigen::Vector3d& v : vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      // The hull is centred on its bounding-box centre (the body's centre of mass approximation).
      *centre = (lo + hi) / 2.0;
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Eigen::Vector3d& v : vertices) hull->addPoint(toBt(v - *centre), false);
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

// The ground plane and the world spec's objects.
void World::Impl::addEnvironment() {
  if (spec.ground.enabled) {
    ground_shape = std::make_unique<GroundPlaneShape>(spec.ground.z);
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
}

Result World::Impl::addObject(const ObjectSpec& object_spec) {
  Result valid = validateObjectSpec(object_spec);
  if (!valid.ok()) return valid;
  if (findObject(object_spec.name) != nullptr) {
    return {Status::kAlreadyExists, describe(object_spec.name) + " already exists"};
  }
  if (world->getNumCollisionObjects() >= kMaxCollisionObjects) {
    return {Status::kInvalidArgument, describe(object_spec.name) + ": the world holds at most " +
                                          std::to_string(kMaxCollisionObjects) + " bodies"};
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
  object->body->setUserPointer(object.get());
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

void World::Impl::wakeObjects() {
  for (const auto& o : objects) {
    if (!o->spec.is_static) o->body->activate();
  }
}

Result World::spawnObject(const ObjectSpec& spec) { return impl_->addObject(spec); }

void World::Impl::removeObject(ObjectRuntime* object) {
  const std::string name = object->spec.name;
  if (grasp_fix) {
    if (grasp_fix->attached() == name) detach(name);
    grasp_fix->forget(name);
  }
  if (suction.held == name) releaseSuction();
  world->removeRigidBody(object->body.get());
  objects.erase(std::find_if(objects.begin(), objects.end(), [&](const auto& o) { return o.get() == object; }));
  wakeObjects();  // what rested on it falls
}

Result World::deleteObject(const std::string& name) {
  ObjectRuntime* object = impl_->findObject(name);
  if (object == nullptr) return {Status::kUnknownObject, "unknown " + describe(name)};
  if (object->conveyor >= 0) return {Status::kInvalidArgument, describe(name) + " is a conveyor's belt: it stays"};
  impl_->removeObject(object);
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
  if (impl_->suction.held == name) state->attached_to = impl_->suction_config->cup_link;
  return Result::success();
}

Result World::setObjectState(const std::string& name, const Eigen::Isometry3d& pose, const Twist& twist) {
  Impl& d = *impl_;
  ObjectRuntime* object = d.findObject(name);
  if (object == nullptr) return {Status::kUnknownObject, "unknown " + describe(name)};
  if (!finite(pose) || !twist.linear.allFinite() || !twist.angular.allFinite()) {
    return {Status::kInvalidArgument, describe(name) + ": pose or twist is not finite"};
  }
  if (object->conveyor >= 0) return {Status::kInvalidArgument, describe(name) + " is a conveyor's belt: it stays"};
  if (object->spec.is_static && (!twist.linear.isZero(0.0) || !twist.angular.isZero(0.0))) {
    return {Status::kStaticObject, describe(name) + " is static: it cannot be given a twist"};
  }
  if (d.grasp_fix) {
    if (d.grasp_fix->attached() == name) d.detach(name);
    d.grasp_fix->forget(name);
  }
  if (d.suction.held == name) d.releaseSuction();
  object->body->setWorldTransform(toBt(pose * object->frame_to_body));
  const Eigen::Vector3d com = pose * object->frame_to_body.translation();
  object->body->setLinearVelocity(toBt(twist.linear + twist.angular.cross(com - pose.translation())));
  object->body->setAngularVelocity(toBt(twist.angular));
  object->body->clearForces();
  d.wakeObjects();  // what rested on it falls; it may land on sleeping objects
  object->body->activate(true);
  // Static bodies have no motion integration: the broadphase must learn the new pose now.
  d.world->updateSingleAabb(object->body.get());
  return Result::success();
}

}  // namespace sixdof_sim
