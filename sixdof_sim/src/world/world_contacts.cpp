#include "world_impl.h"

namespace sixdof_sim {

std::string World::Impl::shapeName(const btCollisionObject* object, int shape_index) const {
  switch (object->getUserIndex()) {
    case kRobotBody: {
      const RobotBody& body = bodies[object->getUserIndex2()];
      if (shape_index >= 0 && shape_index < static_cast<int>(body.shape_links.size())) {
        return body.shape_links[shape_index];
      }
      return body.links.front();
    }
    case kObjectBody:
      return static_cast<const ObjectRuntime*>(object->getUserPointer())->spec.name;
    default:
      return "ground";
  }
}

// Grasp-fix samples of the last step: one per (robot link, dynamic object) pair, over all of the pair's manifolds
// and points: the link's total force on the object and the mean contact point. The total, not a per-point mean:
// Bullet keeps 1 to 4 points per manifold depending on the contact's shape (a finger pad on a cylinder's side is a
// line: often several points on one finger and one on the other), so per-point means of a balanced grip differed
// up to 4x and failed the grasp fix's 0.3 force-ratio test (upright cylinders were never attached).
// Only robot/object manifolds are looked at, and the vectors keep their capacity from step to step.
void World::Impl::collectGraspContacts() {
  grasp_contacts.clear();
  grasp_contact_points.clear();
  const int manifolds = dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    const int points = manifold->getNumContacts();
    if (points == 0) continue;
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    const bool a_robot = a->getUserIndex() == kRobotBody;
    const btCollisionObject* robot = a_robot ? a : b;
    const btCollisionObject* object = a_robot ? b : a;
    if (robot->getUserIndex() != kRobotBody || object->getUserIndex() != kObjectBody || object->isStaticObject()) {
      continue;
    }
    const std::string& object_name = static_cast<const ObjectRuntime*>(object->getUserPointer())->spec.name;
    for (int p = 0; p < points; ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      const std::string link = shapeName(robot, a_robot ? pt.m_index0 : pt.m_index1);
      // Impulse on body A; the object receives it with the sign of its side.
      const btVector3 impulse = pt.m_normalWorldOnB * pt.m_appliedImpulse +
                                pt.m_lateralFrictionDir1 * pt.m_appliedImpulseLateral1 +
                                pt.m_lateralFrictionDir2 * pt.m_appliedImpulseLateral2;
      size_t k = 0;
      while (k < grasp_contacts.size() && (grasp_contacts[k].object != object_name || grasp_contacts[k].link != link)) {
        ++k;
      }
      if (k == grasp_contacts.size()) {
        grasp_contacts.emplace_back();
        grasp_contacts[k].object = object_name;
        grasp_contacts[k].link = link;
        grasp_contact_points.push_back(0);
      }
      GraspContact& gc = grasp_contacts[k];
      gc.force_on_object += toEigen(a_robot ? -impulse : impulse) / dt();
      gc.point += toEigen((pt.getPositionWorldOnA() + pt.getPositionWorldOnB()) * 0.5);
      ++grasp_contact_points[k];
    }
  }
  for (size_t k = 0; k < grasp_contacts.size(); ++k) grasp_contacts[k].point /= grasp_contact_points[k];
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
  const btTransform body_to_object = bodyWorld(body).inverse() * object->body->getWorldTransform();
  grasp_constraint = std::make_unique<btMultiBodyFixedConstraint>(
      multibody.get(), bodies[body].bullet_link, object->body.get(), body_to_object.getOrigin(), btVector3(0, 0, 0),
      body_to_object.getBasis(), btMatrix3x3::getIdentity());
  grasp_constraint->setMaxAppliedImpulse(kGraspConstraintMaxImpulse);
  grasp_constraint->finalizeMultiDof();
  world->addMultiBodyConstraint(grasp_constraint.get());
  setArticulatedWarmstarting(false);
  if (grasp_config->disable_collisions_on_attach) {
    object->body->setCollisionFlags(object->body->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
  }
  pushEvent(GraspEvent::Type::kAttached, name);
}

void World::Impl::detach(const std::string& name) {
  if (!grasp_constraint) return;
  world->removeMultiBodyConstraint(grasp_constraint.get());
  grasp_constraint.reset();
  setArticulatedWarmstarting(true);
  ObjectRuntime* object = findObject(name);
  if (object != nullptr && object->spec.collision) {
    object->body->setCollisionFlags(object->body->getCollisionFlags() & ~btCollisionObject::CF_NO_CONTACT_RESPONSE);
  }
  pushEvent(GraspEvent::Type::kDetached, name);
}

Result World::refreshContacts(const std::string& joint) {
  Impl& d = *impl_;
  const auto found = d.joint_index.find(joint);
  if (found == d.joint_index.end()) return {Status::kUnknownJoint, "unknown joint '" + joint + "'"};
  std::vector<char> moved(d.bodies.size(), 0);
  for (size_t j = 0; j < d.joints.size(); ++j) {
    if (static_cast<int>(j) == found->second || d.joints[j].master == found->second) moved[d.joints[j].body] = 1;
  }
  d.markBodiesBelow(&moved);
  const int manifolds = d.dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    btPersistentManifold* manifold = d.dispatcher->getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    const btCollisionObject* robot = a->getUserIndex() == kRobotBody ? a : b;
    const btCollisionObject* object = robot == a ? b : a;
    if (robot->getUserIndex() == kRobotBody && object->getUserIndex() == kObjectBody &&
        moved[static_cast<size_t>(robot->getUserIndex2())]) {
      manifold->clearManifold();
    }
  }
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
  std::vector<std::string> attached;
  if (impl_->grasp_fix && !impl_->grasp_fix->attached().empty()) attached.push_back(impl_->grasp_fix->attached());
  if (!impl_->suction.held.empty()) attached.push_back(impl_->suction.held);
  return attached;
}

// Read from the collision dispatcher's manifolds, which hold the last step's contact points until the next step.
std::vector<Contact> World::contacts() const {
  const Impl& d = *impl_;
  std::vector<Contact> contacts;
  const int manifolds = d.dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = d.dispatcher->getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      Contact contact;
      contact.body_a = d.shapeName(a, pt.m_index0);
      contact.body_b = d.shapeName(b, pt.m_index1);
      contact.a_is_robot = a->getUserIndex() == kRobotBody;
      contact.b_is_robot = b->getUserIndex() == kRobotBody;
      contact.position_on_b = toEigen(pt.getPositionWorldOnB());
      contact.normal_on_b = toEigen(pt.m_normalWorldOnB);
      contact.depth = pt.getDistance();
      contact.normal_impulse = pt.getAppliedImpulse();
      contacts.push_back(contact);
    }
  }
  return contacts;
}

}  // namespace sixdof_sim
