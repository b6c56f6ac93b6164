#include <Eigen/Eigenvalues>

#include "world_impl.h"

namespace sixdof_sim {

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
    joint_parent_body.push_back(links.at(joint.info.parent_link).body);
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

void World::Impl::createDynamicsWorld() {
  collision_config = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(collision_config.get());
  const btVector3 bound(kBroadphaseHalfExtent, kBroadphaseHalfExtent, kBroadphaseHalfExtent);
  broadphase = std::make_unique<bt32BitAxisSweep3>(-bound, bound, kMaxCollisionObjects, nullptr, true);
  broadphase->getOverlappingPairCache()->setOverlapFilterCallback(&robot_pair_filter);
  solver = std::make_unique<btMultiBodyConstraintSolver>();
  world = std::make_unique<DynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(), collision_config.get());
  world->setGravity(toBt(spec.gravity));
  // Bounds of static and sleeping bodies are not recomputed every step (teleports update them).
  world->setForceUpdateAllAabbs(false);
  btContactSolverInfo& info = world->getSolverInfo();
  info.m_numIterations = options.solver_iterations;
  info.m_timeStep = options.time_step;
  // Contacts: penetration deeper than 0.5 mm is corrected by split impulse (position only, no
  // velocity: objects are not launched); shallower by velocity (ERP 0.2: at most 0.1 m/s).
  // Deterministic order (no randomisation), warm starting for stable resting contacts; iterations end early
  // once the solution has converged.
  info.m_erp = 0.2;
  info.m_erp2 = 0.2;
  info.m_globalCfm = 0.0;
  info.m_splitImpulse = 1;
  info.m_splitImpulsePenetrationThreshold = -0.0005;
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_USE_2_FRICTION_DIRECTIONS;
  info.m_leastSquaresResidualThreshold = kSolverResidualThreshold;
  info.m_articulatedWarmstartingFactor = kArticulatedWarmstartingFactor;
  setArticulatedWarmstarting(true);
  gCalculateCombinedFrictionCallback = &combineFrictionMin;
}

void DynamicsWorld::predictUnconstraintMotion(btScalar time_step) {
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
    btRigidBody* body = m_nonStaticRigidBodies[i];
    if (body->isStaticOrKinematicObject() || !body->isActive()) continue;
    body->applyDamping(time_step);
    body->predictIntegratedTransform(time_step, body->getInterpolationWorldTransform());
  }
  predictMultiBodyTransforms(time_step);
}

void World::Impl::setArticulatedWarmstarting(bool on) {
  on = on && !grasp_constraint && !suction.constraint;  // off while the grasp fix or the suction cup holds
  btContactSolverInfo& info = world->getSolverInfo();
  info.m_solverMode = on ? info.m_solverMode | SOLVER_USE_ARTICULATED_WARMSTARTING
                         : info.m_solverMode & ~SOLVER_USE_ARTICULATED_WARMSTARTING;
}

bool RobotPairFilter::needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const {
  if ((a->m_collisionFilterGroup & b->m_collisionFilterMask) == 0 ||
      (b->m_collisionFilterGroup & a->m_collisionFilterMask) == 0) {
    return false;
  }
  const auto* object_a = static_cast<const btCollisionObject*>(a->m_clientObject);
  const auto* object_b = static_cast<const btCollisionObject*>(b->m_clientObject);
  return object_a->getUserIndex() != kRobotBody || object_b->getUserIndex() != kRobotBody;
}

// The robot as one fixed-base btMultiBody: a Bullet link per body, joint frames at q = 0.
void World::Impl::buildMultibody() {
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
  multibody->setHasSelfCollision(false);  // RobotPairFilter leaves robot/robot pairs out of the broadphase
  multibody->setLinearDamping(0.0);
  multibody->setAngularDamping(0.0);
  multibody->setUseGyroTerm(true);
  world->addMultiBody(multibody.get());
}

// Colliders: one compound per body, a child per URDF collision element.
void World::Impl::addRobotColliders() {
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
    // A moving body without geometry still gets a collider, one that collides with nothing: Bullet solves a
    // link's joint constraints (servo, limit, gear) only within its collider's simulation island.
    const bool shapeless = compound->getNumChildShapes() == 0;
    if (shapeless && body.bullet_link < 0) continue;
    if (shapeless) {
      auto point = std::make_unique<btSphereShape>(kMargin);
      compound->addChildShape(btTransform::getIdentity(), point.get());
      robot_shapes.push_back(std::move(point));
    }
    compound->setMargin(kMargin);
    auto collider = std::make_unique<btMultiBodyLinkCollider>(multibody.get(), body.bullet_link);
    collider->setCollisionShape(compound.get());
    collider->setFriction(friction);
    collider->setRestitution(0.0);
    collider->setUserIndex(kRobotBody);
    collider->setUserIndex2(static_cast<int>(b));
    int group = shapeless ? 0 : btBroadphaseProxy::DefaultFilter;
    int mask = shapeless ? 0 : btBroadphaseProxy::AllFilter;
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
}

// Joint servos and limits (not on mimic joints: their master drives them), friction.
void World::Impl::addJointConstraints() {
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
    runtime.ramp_command = runtime.target_position;
    runtime.ramp_setpoint = std::numeric_limits<double>::quiet_NaN();
    runtime.servo = nullptr;
    if (info.mimic_of.empty()) {
      auto servo = std::make_unique<btMultiBodyJointMotor>(multibody.get(), link, 0.0, info.max_effort * dt());
      servo->setErp(1.0);
      runtime.servo = servo.get();
      world->addMultiBodyConstraint(servo.get());
      robot_constraints.push_back(std::move(servo));
    }
    runtime.friction.reset();
    runtime.friction_in_world = false;
    if (info.friction > 0.0) {
      // Coulomb joint friction as a zero-velocity motor bounded by the friction force.
      runtime.friction = std::make_unique<btMultiBodyJointMotor>(multibody.get(), link, 0.0, info.friction * dt());
      runtime.friction->setVelocityTarget(0.0, 1.0);
    }
    // A mimic joint follows its master (whose limits bound it) and is not held to its own limits, as in MoveIt:
    // vendors' linkages often give them limits that disagree with the master's range.
    if (info.bounded && info.mimic_of.empty()) {
      auto limit = std::make_unique<btMultiBodyJointLimitConstraint>(multibody.get(), link, info.lower, info.upper);
      world->addMultiBodyConstraint(limit.get());
      robot_constraints.push_back(std::move(limit));
    }
    multibody->setJointPos(link, initial_positions[j]);
    multibody->setJointVel(link, 0.0);
  }
}

}  // namespace sixdof_sim
