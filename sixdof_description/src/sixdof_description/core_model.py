"""The designed arm as sixdof_core reads it (the C++ core, through its Python bindings): the named states its
closed-form IK solves, and the joint-space inertia the controller gains come from."""

from __future__ import annotations

import math

import numpy as np

import sixdof_core
from sixdof_description import cad
from sixdof_description.robot_design import GRIPPER_JOINTS, ROOT_LINK, Robot
from sixdof_description.urdf_writer import render_urdf

ARM_GROUP = "arm"
ARM_TIP = "link6"


def robot_model(robot: Robot) -> sixdof_core.RobotModel:
    """The URDF the generator writes, without the meshes (not written yet), and the arm group (the setup
    assistant writes the package's SRDF later, from the named states solved on this model)."""
    arm = f'<group name="{ARM_GROUP}"><chain base_link="{ROOT_LINK}" tip_link="{ARM_TIP}"/></group>'
    srdf = f'<robot name="{robot.name}">{arm}</robot>'
    return sixdof_core.RobotModel(render_urdf(robot, meshes=False), srdf)


def solve_named_states(robot: Robot) -> dict:
    """Each named state of the design (a link6 or tcp pose) solved by the core's closed-form IK: of the solutions
    within the joint limits, the one nearest the design's seed, rounded to 1e-6 rad."""
    model = robot_model(robot)
    states = {}
    for name, st in robot.design["named_states"].items():
        if st["frame"] not in ("link6", "tcp"):
            raise cad.DesignError(f"named state '{name}': frame must be link6 or tcp, got '{st['frame']}'")
        try:
            solver = sixdof_core.AnalyticIkSolver(sixdof_core.KinematicChain(model, ROOT_LINK, st["frame"]))
        except sixdof_core.AnalyticIkUnsupported as error:
            raise cad.DesignError(f"named state '{name}': the arm has no closed-form IK: {error}") from error
        target = sixdof_core.pose_from_xyz_rpy(*st["xyz"], *[math.radians(a) for a in st["rpy_deg"]])
        seed = np.asarray(st["seed"], dtype=float)
        found = solver.solve_all(target, seed)
        if not found:
            raise cad.DesignError(f"named state '{name}': {st['frame']} pose {st['xyz']} rpy {st['rpy_deg']} is "
                                  f"unreachable ({found.message})")
        q = np.round(min(found.solutions, key=lambda solution: float(np.linalg.norm(solution - seed))), 6)
        perr, rerr = sixdof_core.pose_error(solver.chain.forward(q), target)
        if perr > 1e-5 or rerr > 1e-5:
            raise cad.DesignError(f"named state '{name}': rounded solution misses the pose by {perr:.3g} m")
        states[name] = q
    return states


def joint_space_inertia(robot: Robot, arm_positions: np.ndarray) -> np.ndarray:
    """The arm's joint-space inertia matrix at arm_positions with the gripper (if any) open: the sum over the
    links of m Jv^T Jv + Jw^T I Jw, with each link's Jacobian at its centre of mass and its inertia in the root
    frame."""
    model = robot_model(robot)
    state = sixdof_core.RobotState(model)
    state.set_group_positions(ARM_GROUP, arm_positions)
    if robot.tool_joints:
        state.set_joint_position(GRIPPER_JOINTS[0], float(robot.design["gripper_states"]["open"]))
    inertia_matrix = np.zeros((len(arm_positions), len(arm_positions)))
    for link in model.links:
        if link.inertial is None:
            continue
        jacobian = state.jacobian(ARM_GROUP, link.name, link.inertial.origin[:3, 3])
        rotation = state.link_pose(link.name)[:3, :3] @ link.inertial.origin[:3, :3]
        inertia = rotation @ link.inertial.inertia @ rotation.T
        linear, angular = jacobian[:3], jacobian[3:]
        inertia_matrix += link.inertial.mass * linear.T @ linear + angular.T @ inertia @ angular
    return inertia_matrix
