"""Plain-numpy kinematics and trajectory helpers of the commander (no ROS communication, unit-testable).

Forward kinematics and the geometric Jacobian of a group from the robot model move_group serves
(get_robot_model: joint origins, axes and types as the core's RobotModel reads them; the rostest
robot_model_query checks the Jacobian against finite differences of move_group's compute_fk), clamping a state
into the joint limits, and an iterative parabolic time parameterization of a joint path.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from scipy.spatial.transform import Rotation

from .exceptions import SixdofCommanderError
from .robot_model import Group, Joint, RobotDescription
from .transforms import homogeneous


def joint_motion(joint: Joint, value: float) -> np.ndarray:
    """4x4 transform the joint adds at `value` (in its own frame, after its origin)."""
    axis = np.asarray(joint.axis, dtype=float)
    norm = np.linalg.norm(axis)
    if joint.type in ("revolute", "continuous"):
        return homogeneous((0.0, 0.0, 0.0), Rotation.from_rotvec(axis / norm * value).as_matrix())
    if joint.type == "prismatic":
        return homogeneous(axis / norm * value, np.eye(3))
    return np.eye(4)


def chain_transforms(
    urdf: RobotDescription, tip_link: str, positions: Mapping[str, float]
) -> list[tuple[Joint, np.ndarray]]:
    """(joint, joint frame in the root link after its origin, before its motion) for every joint from the root
    down to tip_link, and the tip link's pose last (as (None, pose)). Joints missing from positions are at 0."""
    frames = []
    transform = np.eye(4)
    for joint in urdf.chain(urdf.root_link, tip_link):
        transform = transform @ joint.origin
        frames.append((joint, transform.copy()))
        transform = transform @ joint_motion(joint, positions.get(joint.name, 0.0))
    frames.append((None, transform))
    return frames


def link_pose(urdf: RobotDescription, link: str, positions: Mapping[str, float]) -> np.ndarray:
    """4x4 pose of `link` in the URDF root link."""
    return chain_transforms(urdf, link, positions)[-1][1]


def jacobian(
    urdf: RobotDescription,
    group: Group,
    positions: Mapping[str, float],
    reference_point: Sequence[float] = (0.0, 0.0, 0.0),
) -> np.ndarray:
    """Geometric Jacobian (6 x active joints; rows vx, vy, vz, wx, wy, wz in the root frame) of the point
    `reference_point` (in the group's tip link frame) of the group's tip link, as MoveIt's getJacobian."""
    frames = chain_transforms(urdf, group.tip_link, positions)
    tip = frames[-1][1]
    point = (tip @ np.append(np.asarray(reference_point, dtype=float), 1.0))[:3]
    columns = {joint.name: i for i, joint in enumerate(group.joints)}
    result = np.zeros((6, len(group.joints)))
    for joint, frame in frames[:-1]:
        if joint.type == "fixed" or joint.name not in columns:
            if joint.mimic is not None and joint.mimic in columns:
                raise SixdofCommanderError(
                    f"get_jacobian_matrix: joint '{joint.name}' mimics '{joint.mimic}'; groups with mimic joints "
                    "on the tip's chain are not supported"
                )
            continue
        axis = frame[:3, :3] @ (np.asarray(joint.axis, dtype=float) / np.linalg.norm(joint.axis))
        column = columns[joint.name]
        if joint.type == "prismatic":
            result[:3, column] = axis
        else:
            result[:3, column] = np.cross(axis, point - frame[:3, 3])
            result[3:, column] = axis
    return result


def bounded(joint: Joint, value: float) -> float:
    """value clamped into the joint's limits (continuous joints: wrapped into [-pi, pi])."""
    if joint.type == "continuous":
        return (value + math.pi) % (2.0 * math.pi) - math.pi
    return min(max(value, joint.lower), joint.upper)


def random_value(joint: Joint, rng: np.random.Generator) -> float:
    """A uniform random value within the joint's limits ([-pi, pi] for unbounded revolute joints)."""
    lower = joint.lower if math.isfinite(joint.lower) else -math.pi
    upper = joint.upper if math.isfinite(joint.upper) else math.pi
    return float(rng.uniform(lower, upper))


def iterative_parabolic_times(
    path: np.ndarray, max_velocity: np.ndarray, max_acceleration: np.ndarray, max_iterations: int = 1000
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(times from start, velocities, accelerations) of a joint path (points x joints) that starts and ends at
    rest, MoveIt's iterative parabolic scheme: each segment first gets the shortest duration its velocity
    limits allow, then segment durations around every point whose finite-difference acceleration exceeds a
    limit are stretched until none does."""
    count = len(path)
    if count == 1:
        zeros = np.zeros_like(path)
        return np.zeros(1), zeros, zeros
    deltas = np.diff(path, axis=0)
    durations = np.max(np.abs(deltas) / max_velocity, axis=1)
    durations = np.maximum(durations, 1e-6)

    def point_velocities(durations: np.ndarray) -> np.ndarray:
        segment = deltas / durations[:, None]
        velocities = np.zeros_like(path)
        velocities[1:-1] = 0.5 * (segment[:-1] + segment[1:])
        return velocities

    for _ in range(max_iterations):
        velocities = point_velocities(durations)
        changed = False
        for i in range(count - 1):
            # The acceleration over segment i, from the velocity at its start to the one at its end.
            acceleration = np.abs(velocities[i + 1] - velocities[i]) / durations[i]
            ratio = np.max(acceleration / max_acceleration)
            if ratio > 1.0 + 1e-9:
                durations[i] *= math.sqrt(ratio) * 1.0001
                changed = True
        if not changed:
            break
    else:
        raise SixdofCommanderError(
            f"retime_trajectory: the accelerations did not settle within the limits after {max_iterations} passes"
        )
    velocities = point_velocities(durations)
    times = np.concatenate(([0.0], np.cumsum(durations)))
    accelerations = np.zeros_like(path)
    accelerations[1:-1] = (velocities[2:] - velocities[:-2]) / (times[2:] - times[:-2])[:, None]
    accelerations[0] = (velocities[1] - velocities[0]) / durations[0]
    accelerations[-1] = (velocities[-1] - velocities[-2]) / durations[-1]
    return times, velocities, accelerations
