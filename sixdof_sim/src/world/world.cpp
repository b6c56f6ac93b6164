#include <set>

#include "sixdof_sim/conveyor.h"
#include "world_impl.h"

namespace sixdof_sim {

void World::Impl::build() {
  createDynamicsWorld();
  buildMultibody();
  addRobotColliders();
  addJointConstraints();
  addMimicConstraints();
  addEnvironment();
  addConveyors();
  refreshKinematics();
}

void World::Impl::destroy() {
  if (world) {
    if (grasp_constraint) world->removeMultiBodyConstraint(grasp_constraint.get());
    if (suction.constraint) world->removeMultiBodyConstraint(suction.constraint.get());
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
  suction = SuctionRuntime();
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

void World::Impl::refreshKinematics() {
  multibody->updateCollisionObjectWorldTransforms(scratch_rot, scratch_pos);
  body_world_current = false;
}

const btTransform& World::Impl::bodyWorld(int body) const {
  if (!body_world_current) {
    multibody->forwardKinematics(scratch_rot, scratch_pos);
    body_world.resize(bodies.size());
    for (size_t b = 0; b < bodies.size(); ++b) {
      body_world[b] = btTransform(scratch_rot[b].inverse(), scratch_pos[b]);
    }
    body_world_current = true;
  }
  return body_world[body];
}

void World::Impl::applyCommands() {
  // A linkage's squeeze: its master's bound plus that of each mimic joint beside it (on the same parent body, as the
  // other finger of a parallel gripper), a mimic joint's bound being its own limit unless its master's command
  // lowered it. Mimic joints in series (a pad on a knuckle) move with the master's finger and add no squeeze.
  for (JointRuntime& runtime : joints) {
    runtime.linkage_bound = runtime.max_effort;
    runtime.drives_linkage = false;
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    const int master = joints[j].master;
    if (master >= 0) joints[master].drives_linkage = true;
    if (master < 0 || joint_parent_body[j] != joint_parent_body[static_cast<size_t>(master)]) continue;
    joints[master].linkage_bound +=
        std::abs(joint_infos[j].mimic_multiplier) * std::min(joint_infos[j].max_effort, joints[master].max_effort);
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    JointRuntime& runtime = joints[j];
    const JointInfo& info = joint_infos[j];
    const int link = bodies[runtime.body].bullet_link;
    if (runtime.master >= 0) {
      // No servo: its master's drives the whole linkage through the coupling (gears and projectMimicMotion); a servo
      // of its own would pull a single light link against the coupling in the solver. In effort mode it gets its
      // share of the master's effort.
      const JointRuntime& master = joints[runtime.master];
      runtime.mode = master.mode;
      if (runtime.mode == JointControlMode::kEffort) {
        multibody->addJointTorque(link, info.mimic_multiplier * master.effort);
      }
    } else {
      switch (runtime.mode) {
        case JointControlMode::kPosition:
        case JointControlMode::kVelocity: {
          const double gain = runtime.mode == JointControlMode::kPosition ? options.position_gain * dt() : 0.0;
          double position = runtime.target_position;
          double velocity = runtime.target_velocity;
          if (runtime.drives_linkage && runtime.mode == JointControlMode::kPosition && info.max_velocity > 0.0) {
            rampLinkage(runtime, info.max_velocity, multibody->getJointPos(link), &position, &velocity);
          }
          runtime.servo->setPositionTarget(position, gain);
          runtime.servo->setVelocityTarget(velocity, 1.0);
          runtime.servo->setMaxAppliedImpulse(runtime.linkage_bound * dt());
          break;
        }
        case JointControlMode::kEffort:
          runtime.servo->setMaxAppliedImpulse(0.0);
          multibody->addJointTorque(link, runtime.effort);
          break;
      }
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

// Each joint's applied effort after a step: a master's servo pushes for its whole linkage, of which the master
// reports its own share (its bound's part of the linkage's); a mimic joint reports its multiplier times that.
void World::Impl::readAppliedEfforts() {
  for (JointRuntime& runtime : joints) {
    if (runtime.master >= 0) continue;
    runtime.applied_effort = runtime.mode == JointControlMode::kEffort ? runtime.effort
                                                                       : runtime.servo->getAppliedImpulse(0) / dt() *
                                                                             runtime.max_effort / runtime.linkage_bound;
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    JointRuntime& runtime = joints[j];
    if (runtime.master >= 0)
      runtime.applied_effort = joint_infos[j].mimic_multiplier * joints[runtime.master].applied_effort;
  }
}

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
  impl_->resolver = sixdof_core::PackageResolver::fromSearchRoots(options.package_search_roots);
  try {
    impl_->model = std::make_shared<const sixdof_core::RobotModel>(urdf_xml, "", impl_->resolver);
    impl_->robot = describeRobot(*impl_->model, urdf_xml);
  } catch (const sixdof_core::RobotModelError& e) {
    throw WorldError(e.what());
  } catch (const std::invalid_argument& e) {
    throw WorldError(e.what());
  }
  std::set<std::string> names;
  for (const ObjectSpec& object : world.objects) {
    if (!names.insert(object.name).second) {
      throw WorldError("world '" + world.name + "': duplicate object '" + object.name + "'");
    }
  }
  const Result conveyors = validateConveyors(world);
  if (!conveyors.ok()) throw WorldError("world '" + world.name + "': " + conveyors.message);
  impl_->buildStructure();
  impl_->grasp_config = impl_->robot.grasp_fix ? impl_->robot.grasp_fix : options.grasp_fix_config;
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
  impl_->configureSuction(urdf_xml);
  try {
    impl_->build();
  } catch (const std::invalid_argument& e) {
    throw WorldError(e.what());
  }
}

World::~World() { impl_->destroy(); }

void World::step(std::uint64_t n) {
  Impl& d = *impl_;
  for (std::uint64_t i = 0; i < n; ++i) {
    if (d.pre_step) d.pre_step(simTime());
    d.applyCommands();
    d.world->getSolverInfo().m_numIterations = d.linkageSolverIterations();
    // maxSubSteps = 0: exactly one internal step of time_step (no accumulator, no interpolation). The step
    // leaves the robot's colliders where its links are; their frames (body_world) follow when asked for.
    d.world->stepSimulation(d.dt(), 0, d.dt());
    ++d.steps;
    d.body_world_current = false;
    d.readAppliedEfforts();
    if (d.grasp_enabled) {
      d.collectGraspContacts();
      const GraspDecision decision = d.grasp_fix->update(simTime(), d.grasp_contacts);
      for (const std::string& object : decision.detach) d.detach(object);
      for (const std::string& object : decision.attach) d.attach(object);
    }
    d.stepSuction();
    if (!d.spec.sources.empty()) d.stepSources();
    if (!d.spec.sinks.empty()) d.stepSinks();
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
  if (d.grasp_fix) d.grasp_fix->reset();
  d.build();
}

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
