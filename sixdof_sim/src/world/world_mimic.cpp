#include "world_impl.h"

namespace sixdof_sim {

// Mimic joints: a gear constraint q_mimic - multiplier * q_master = offset couples them in the solver, so a
// parallel gripper stays symmetric when an object pushes one finger (independent servos alone let a squeezed object
// and both fingers drift sideways as a unit once both servos saturate); projectMimicMotion makes the coupling exact.
void World::Impl::addMimicConstraints() {
  mimic_rows.clear();
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
    MimicRow row;
    row.link = link;
    row.master_link = master_link;
    row.dof = 6 + multibody->getLink(link).m_dofOffset;
    row.master_dof = 6 + multibody->getLink(master_link).m_dofOffset;
    row.multiplier = info.mimic_multiplier;
    row.offset = info.mimic_offset;
    mimic_rows.push_back(row);
  }
  mimic_limits.clear();
  for (size_t j = 0; j < joints.size(); ++j) {
    const bool master = std::any_of(joints.begin(), joints.end(),
                                    [j](const JointRuntime& other) { return other.master == static_cast<int>(j); });
    if (!master || !joint_infos[j].bounded) continue;
    MimicLimit limit;
    limit.link = bodies[joints[j].body].bullet_link;
    limit.dof = 6 + multibody->getLink(limit.link).m_dofOffset;
    limit.lower = joint_infos[j].lower;
    limit.upper = joint_infos[j].upper;
    mimic_limits.push_back(limit);
  }
  const auto rows = static_cast<Eigen::Index>(mimic_rows.size() + mimic_limits.size());
  const auto dofs = static_cast<Eigen::Index>(6 + multibody->getNumDofs());
  mimic_unit.assign(static_cast<size_t>(dofs), 0.0);
  mimic_response.resize(dofs, rows);
  mimic_active.reserve(static_cast<size_t>(rows));
  mimic_delta.resize(dofs);
  mimic_linkage_delta.resize(dofs);
  mimic_dofs.clear();
  for (const MimicRow& row : mimic_rows) {
    for (const int dof : {row.dof, row.master_dof}) {
      if (std::find(mimic_dofs.begin(), mimic_dofs.end(), dof) == mimic_dofs.end()) mimic_dofs.push_back(dof);
    }
  }
  // The bodies a linkage moves: the child body of each mimic joint and master, and every body below them.
  linkage_bodies.assign(bodies.size(), 0);
  for (const MimicRow& row : mimic_rows) {
    for (const int link : {row.link, row.master_link}) {
      for (size_t b = 0; b < bodies.size(); ++b) {
        if (bodies[b].bullet_link == link) linkage_bodies[b] = 1;
      }
    }
  }
  markBodiesBelow(&linkage_bodies);
  static_cast<DynamicsWorld*>(world.get())->after_solve =
      mimic_rows.empty() ? std::function<void()>() : [this] { projectMimicMotion(); };
}

// The solver's gears give way where a light linkage is squeezed between its master's servo and an object (up to
// 0.6 rad on the adaptive gripper of test_fixture_grippers: its iterations end first). So after the solver, the
// joint velocities get the impulses that satisfy every coupling exactly, found together (J M^-1 J^T lambda = b):
// each mimic joint's velocity becomes its share of its master's, plus the rate that removes any gap from its share
// within the step. The impulses are weighed by the whole multibody's inertia, so a light link follows its master
// rather than the master following it. That shares the mimic joints' motion with the master, which the solver's
// limit no longer sees: a master that would end the step past a limit is solved again with its velocity the one
// that ends it at the limit (fingers pressed on the table drove finger_joint to 1.9 rad of [0, 0.8]). Joint
// positions integrate linearly from these velocities, so the coupling holds at every step's end.
void World::Impl::projectMimicMotion() {
  for (int l = 0; l < multibody->getNumLinks(); ++l) {
    const btMultiBodyLinkCollider* collider = multibody->getLink(l).m_collider;
    if (collider != nullptr && collider->getActivationState() == ISLAND_SLEEPING) return;
  }
  const btScalar* velocity = multibody->getVelocityVector();
  const auto response = [this](int column, int dof, int master_dof, double multiplier) {
    mimic_unit[static_cast<size_t>(dof)] = 1.0;
    if (master_dof >= 0) mimic_unit[static_cast<size_t>(master_dof)] = -multiplier;
    multibody->calcAccelerationDeltasMultiDof(mimic_unit.data(), mimic_response.col(column).data(), mimic_scratch_r,
                                              mimic_scratch_v);
    mimic_unit[static_cast<size_t>(dof)] = 0.0;
    if (master_dof >= 0) mimic_unit[static_cast<size_t>(master_dof)] = 0.0;
  };
  const int couplings = static_cast<int>(mimic_rows.size());
  for (int r = 0; r < couplings; ++r) {
    const MimicRow& row = mimic_rows[static_cast<size_t>(r)];
    response(r, row.dof, row.master_dof, row.multiplier);
  }
  mimic_active.clear();
  for (int r = 0; r < couplings; ++r) mimic_active.push_back(r);
  solveMimicRows();
  bool limited = false;
  for (size_t l = 0; l < mimic_limits.size(); ++l) {
    MimicLimit& limit = mimic_limits[l];
    const double next = multibody->getJointPos(limit.link) + (velocity[limit.dof] + mimic_delta[limit.dof]) * dt();
    if (next <= limit.upper && next >= limit.lower) continue;
    limit.reached = next > limit.upper ? limit.upper : limit.lower;
    const int column = couplings + static_cast<int>(l);
    response(column, limit.dof, -1, 0.0);
    mimic_active.push_back(column);
    limited = true;
  }
  if (limited) solveMimicRows();
  // Only the linkages' joints change: the rows touch nothing else, so they hold as solved, and the arm keeps the
  // velocities its servos and contacts gave it.
  mimic_linkage_delta.setZero();
  for (const int dof : mimic_dofs) mimic_linkage_delta[dof] = mimic_delta[dof];
  multibody->applyDeltaVeeMultiDof(mimic_linkage_delta.data(), 1.0);
}

// The impulses of the active columns (couplings, then limits) and the velocity change they make (mimic_delta).
void World::Impl::solveMimicRows() {
  const btScalar* velocity = multibody->getVelocityVector();
  const auto n = static_cast<Eigen::Index>(mimic_active.size());
  const auto couplings = static_cast<int>(mimic_rows.size());
  mimic_matrix.resize(n, n);
  mimic_rhs.resize(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const int column = mimic_active[static_cast<size_t>(a)];
    for (Eigen::Index b = 0; b < n; ++b) {
      const auto col = mimic_response.col(mimic_active[static_cast<size_t>(b)]);
      if (column < couplings) {
        const MimicRow& row = mimic_rows[static_cast<size_t>(column)];
        mimic_matrix(a, b) = col[row.dof] - row.multiplier * col[row.master_dof];
      } else {
        mimic_matrix(a, b) = col[mimic_limits[static_cast<size_t>(column - couplings)].dof];
      }
    }
    if (column < couplings) {
      const MimicRow& row = mimic_rows[static_cast<size_t>(column)];
      const double gap =
          multibody->getJointPos(row.link) - row.multiplier * multibody->getJointPos(row.master_link) - row.offset;
      mimic_rhs[a] = -gap / dt() - (velocity[row.dof] - row.multiplier * velocity[row.master_dof]);
    } else {
      const MimicLimit& limit = mimic_limits[static_cast<size_t>(column - couplings)];
      mimic_rhs[a] = (limit.reached - multibody->getJointPos(limit.link)) / dt() - velocity[limit.dof];
    }
  }
  mimic_solver.compute(mimic_matrix);
  mimic_impulse = mimic_solver.solve(mimic_rhs);
  mimic_delta.setZero();
  for (Eigen::Index a = 0; a < n; ++a) {
    mimic_delta += mimic_response.col(mimic_active[static_cast<size_t>(a)]) * mimic_impulse[a];
  }
}

// A linkage's drive moves at most at its URDF velocity limit, as a gripper's motor does: a jump of its command (open,
// close) becomes a setpoint ramping from where the linkage is, so both fingers leave an object together. Commanded
// at once, the servo opened a jaw at 57 rad/s while the solver still pressed the other finger against the object
// (coupled by its gear only), flinging a released sphere off its target. Against an object the ramp goes on to
// the command, so the squeeze is the servo's full bound as without it; commands within the limit pass unchanged.
void World::Impl::rampLinkage(JointRuntime& runtime, double max_velocity, double q, double* position,
                              double* velocity) const {
  const double step = max_velocity * dt();
  if (std::abs(*position - runtime.ramp_command) > step) runtime.ramp_setpoint = q;
  runtime.ramp_command = *position;
  if (std::isnan(runtime.ramp_setpoint)) return;
  const double remaining = *position - runtime.ramp_setpoint;
  if (std::abs(remaining) <= step) {
    runtime.ramp_setpoint = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  runtime.ramp_setpoint += std::copysign(step, remaining);
  *position = runtime.ramp_setpoint;
  *velocity = std::copysign(max_velocity, remaining);
}

void World::Impl::markBodiesBelow(std::vector<char>* marked) const {
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t j = 0; j < joints.size(); ++j) {
      if ((*marked)[joint_parent_body[j]] && !(*marked)[joints[j].body]) {
        (*marked)[joints[j].body] = 1;
        grew = true;
      }
    }
  }
}

int World::Impl::linkageSolverIterations() const {
  const int manifolds = mimic_rows.empty() ? 0 : dispatcher->getNumManifolds();
  for (int m = 0; m < manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    if (manifold->getNumContacts() == 0) continue;
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    const btCollisionObject* robot = a->getUserIndex() == kRobotBody ? a : b;
    const btCollisionObject* object = robot == a ? b : a;
    if (robot->getUserIndex() == kRobotBody && object->getUserIndex() == kObjectBody && !object->isStaticObject() &&
        linkage_bodies[static_cast<size_t>(robot->getUserIndex2())]) {
      return std::max(grasp_constraint ? kLinkageHoldSolverIterations : kLinkageSqueezeSolverIterations,
                      options.solver_iterations);
    }
  }
  return options.solver_iterations;
}

}  // namespace sixdof_sim
