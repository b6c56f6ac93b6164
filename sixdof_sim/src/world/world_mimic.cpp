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
  const auto rows = static_cast<Eigen::Index>(mimic_rows.size());
  const auto dofs = static_cast<Eigen::Index>(6 + multibody->getNumDofs());
  mimic_unit.assign(static_cast<size_t>(dofs), 0.0);
  mimic_response.resize(dofs, rows);
  mimic_matrix.resize(rows, rows);
  mimic_rhs.resize(rows);
  mimic_impulse.resize(rows);
  mimic_delta.resize(dofs);
  mimic_linkage_delta.resize(dofs);
  mimic_dofs.clear();
  for (const MimicRow& row : mimic_rows) {
    for (const int dof : {row.dof, row.master_dof}) {
      if (std::find(mimic_dofs.begin(), mimic_dofs.end(), dof) == mimic_dofs.end()) mimic_dofs.push_back(dof);
    }
  }
  mimic_solver = Eigen::LDLT<Eigen::MatrixXd>(rows);
  static_cast<DynamicsWorld*>(world.get())->after_solve =
      mimic_rows.empty() ? std::function<void()>() : [this] { projectMimicMotion(); };
}

// The solver's gears give way where a light linkage is squeezed between its master's servo and an object (up to
// 0.6 rad on the adaptive gripper of test_fixture_grippers: its iterations end first). So after the solver, the
// joint velocities get the impulses that satisfy every coupling exactly, found together (J M^-1 J^T lambda = b):
// each mimic joint's velocity becomes its share of its master's, plus the rate that removes any gap from its share
// within the step. The impulses are weighed by the whole multibody's inertia, so a light link follows its master
// rather than the master following it. Joint positions integrate linearly from these velocities, so the coupling
// holds at every step's end.
void World::Impl::projectMimicMotion() {
  for (int l = 0; l < multibody->getNumLinks(); ++l) {
    const btMultiBodyLinkCollider* collider = multibody->getLink(l).m_collider;
    if (collider != nullptr && collider->getActivationState() == ISLAND_SLEEPING) return;
  }
  const btScalar* velocity = multibody->getVelocityVector();
  for (size_t r = 0; r < mimic_rows.size(); ++r) {
    const MimicRow& row = mimic_rows[r];
    mimic_unit[static_cast<size_t>(row.dof)] = 1.0;
    mimic_unit[static_cast<size_t>(row.master_dof)] = -row.multiplier;
    multibody->calcAccelerationDeltasMultiDof(
        mimic_unit.data(), mimic_response.col(static_cast<Eigen::Index>(r)).data(), mimic_scratch_r, mimic_scratch_v);
    mimic_unit[static_cast<size_t>(row.dof)] = 0.0;
    mimic_unit[static_cast<size_t>(row.master_dof)] = 0.0;
    const double gap =
        multibody->getJointPos(row.link) - row.multiplier * multibody->getJointPos(row.master_link) - row.offset;
    const double relative = velocity[row.dof] - row.multiplier * velocity[row.master_dof];
    mimic_rhs[static_cast<Eigen::Index>(r)] = -gap / dt() - relative;
  }
  for (size_t r = 0; r < mimic_rows.size(); ++r) {
    const MimicRow& row = mimic_rows[r];
    mimic_matrix.row(static_cast<Eigen::Index>(r)) =
        mimic_response.row(row.dof) - row.multiplier * mimic_response.row(row.master_dof);
  }
  mimic_solver.compute(mimic_matrix);
  mimic_impulse = mimic_solver.solve(mimic_rhs);
  mimic_delta.noalias() = mimic_response * mimic_impulse;
  // Only the linkages' joints change: the rows touch nothing else, so they hold as solved, and the arm keeps the
  // velocities its servos and contacts gave it.
  mimic_linkage_delta.setZero();
  for (const int dof : mimic_dofs) mimic_linkage_delta[dof] = mimic_delta[dof];
  multibody->applyDeltaVeeMultiDof(mimic_linkage_delta.data(), 1.0);
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

}  // namespace sixdof_sim
