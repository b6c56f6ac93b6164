"""KDL chains and a numeric IK with seeded restarts (PyKDL), shared by the generator and the tests."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import PyKDL as kdl  # noqa: N813 (KDL's own name)


@dataclass(frozen=True)
class JointSpec:
    """One URDF joint as the kinematics needs it (origin in the parent link, axis in the child link)."""

    name: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    axis: tuple[float, float, float]
    joint_type: str  # revolute | prismatic | fixed
    lower: float = 0.0
    upper: float = 0.0


def frame(xyz: Sequence[float], rpy: Sequence[float]) -> kdl.Frame:
    return kdl.Frame(kdl.Rotation.RPY(*[float(a) for a in rpy]), kdl.Vector(*[float(v) for v in xyz]))


def segment(spec: JointSpec, inertia: kdl.RigidBodyInertia | None = None) -> kdl.Segment:
    """The child link of `spec` as a KDL segment (same convention as kdl_parser)."""
    origin = frame(spec.xyz, spec.rpy)
    axis = origin.M * kdl.Vector(*spec.axis)
    if spec.joint_type == "revolute":
        joint = kdl.Joint(spec.name, origin.p, axis, kdl.Joint.RotAxis)
    elif spec.joint_type == "prismatic":
        joint = kdl.Joint(spec.name, origin.p, axis, kdl.Joint.TransAxis)
    elif spec.joint_type == "fixed":
        joint = kdl.Joint(spec.name, kdl.Joint.Fixed)
    else:
        raise ValueError(f"joint '{spec.name}': unsupported type '{spec.joint_type}'")
    if inertia is None:
        return kdl.Segment(spec.name + "_child", joint, origin)
    return kdl.Segment(spec.name + "_child", joint, origin, inertia)


def chain(specs: Sequence[JointSpec], inertias: Sequence[kdl.RigidBodyInertia] | None = None) -> kdl.Chain:
    out = kdl.Chain()
    for i, spec in enumerate(specs):
        out.addSegment(segment(spec, None if inertias is None else inertias[i]))
    return out


def to_array(q: kdl.JntArray) -> np.ndarray:
    return np.array([q[i] for i in range(q.rows())])


def to_jnt(values: Sequence[float]) -> kdl.JntArray:
    q = kdl.JntArray(len(values))
    for i, v in enumerate(values):
        q[i] = float(v)
    return q


def fk(kchain: kdl.Chain, q: Sequence[float]) -> kdl.Frame:
    out = kdl.Frame()
    status = kdl.ChainFkSolverPos_recursive(kchain).JntToCart(to_jnt(q), out)
    if status < 0:
        raise RuntimeError(f"KDL forward kinematics failed with status {status}")
    return out


def pose_error(a: kdl.Frame, b: kdl.Frame) -> tuple[float, float]:
    """(position error in m, rotation angle error in rad) between two frames."""
    twist = kdl.diff(a, b)
    return twist.vel.Norm(), twist.rot.Norm()


@dataclass(frozen=True)
class IkResult:
    success: bool
    q: np.ndarray
    position_error: float
    rotation_error: float
    solutions_found: int


def solve_ik(
    kchain: kdl.Chain,
    lower: Sequence[float],
    upper: Sequence[float],
    target: kdl.Frame,
    seed: Sequence[float],
    *,
    tolerance: float = 1e-9,
    max_iterations: int = 500,
    restarts: int = 100,
    random_seed: int = 0,
) -> IkResult:
    """Newton-Raphson IK within joint limits from `seed`, then from seeded random starts.

    Returns the converged solution closest to `seed` (so named states are the natural branch the seed
    describes), or success=False with the best attempt.
    """
    n = kchain.getNrOfJoints()
    lo, hi = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    fk_solver = kdl.ChainFkSolverPos_recursive(kchain)
    vel_solver = kdl.ChainIkSolverVel_pinv(kchain)
    solver = kdl.ChainIkSolverPos_NR_JL(
        kchain, to_jnt(lo), to_jnt(hi), fk_solver, vel_solver, max_iterations, tolerance
    )
    rng = np.random.RandomState(random_seed)
    seed_a = np.asarray(seed, dtype=float)
    # Random starts are drawn from the finite part of each range (multi-turn joints: one turn).
    span_lo, span_hi = np.maximum(lo, -math.pi), np.minimum(hi, math.pi)
    starts = [seed_a] + [rng.uniform(span_lo, span_hi) for _ in range(restarts)]
    best: tuple[float, np.ndarray] | None = None
    found = 0
    fallback = (math.inf, math.inf, seed_a)
    for start in starts:
        out = kdl.JntArray(n)
        solver.CartToJnt(to_jnt(start), target, out)
        q = to_array(out)
        perr, rerr = pose_error(fk(kchain, q), target)
        inside = bool(np.all(q >= lo - 1e-12) and np.all(q <= hi + 1e-12))
        if perr < 1e-7 and rerr < 1e-7 and inside:
            found += 1
            dist = float(np.linalg.norm(q - seed_a))
            if best is None or dist < best[0]:
                best = (dist, q)
        elif perr + rerr < fallback[0] + fallback[1]:
            fallback = (perr, rerr, q)
    if best is None:
        return IkResult(False, fallback[2], fallback[0], fallback[1], 0)
    perr, rerr = pose_error(fk(kchain, best[1]), target)
    return IkResult(True, best[1], perr, rerr, found)
