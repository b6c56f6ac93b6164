"""geometry_msgs and tuple adapters of scipy's Rotation, the project's one rotation implementation.

Quaternions are (x, y, z, w) as in geometry_msgs; roll/pitch/yaw are fixed-axis angles, R = Rz(yaw) Ry(pitch)
Rx(roll), as tf2's setRPY/getRPY and URDF's rpy (scipy's extrinsic "xyz" sequence).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from geometry_msgs.msg import Pose
from scipy.spatial.transform import Rotation

Quaternion = tuple[float, float, float, float]


def _tuple(q: np.ndarray) -> Quaternion:
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Quaternion (x, y, z, w) of rotations about the fixed x, y, z axes: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return _tuple(Rotation.from_euler("xyz", (roll, pitch, yaw)).as_quat())


def matrix_from_quaternion(q: Sequence[float]) -> np.ndarray:
    """3x3 rotation matrix of a quaternion (x, y, z, w), normalized first; ValueError for a zero quaternion."""
    return Rotation.from_quat(q).as_matrix()


def quaternion_from_matrix(m: np.ndarray) -> Quaternion:
    """Unit quaternion (x, y, z, w) with w >= 0 of a 3x3 rotation matrix."""
    q = Rotation.from_matrix(m).as_quat()
    return _tuple(-q if q[3] < 0.0 else q)


def rpy_from_quaternion(q: Sequence[float]) -> tuple[float, float, float]:
    """Fixed-axis (roll, pitch, yaw) of a quaternion, with pitch in [-pi/2, pi/2] (tf2 getRPY). At gimbal lock
    (pitch +-pi/2) only roll -+ yaw is defined: yaw is 0, as tf2 reports it."""
    m = matrix_from_quaternion(q)
    if abs(m[2, 0]) >= 1.0 - 1e-12:
        # scipy would warn here; the same answer (yaw 0) without the warning.
        pitch = -math.copysign(math.pi / 2.0, m[2, 0])
        return (math.atan2(-m[1, 2], m[1, 1]), pitch, 0.0)
    roll, pitch, yaw = Rotation.from_matrix(m).as_euler("xyz")
    return (float(roll), float(pitch), float(yaw))


def matrix_from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """3x3 rotation matrix Rz(yaw) Ry(pitch) Rx(roll)."""
    return Rotation.from_euler("xyz", (roll, pitch, yaw)).as_matrix()


def rotation_angle(a: Sequence[float], b: Sequence[float]) -> float:
    """Angle (rad, in [0, pi]) of the rotation between two quaternions (x, y, z, w); q and -q are the same."""
    return float((Rotation.from_quat(a).inv() * Rotation.from_quat(b)).magnitude())


def homogeneous(translation: Sequence[float], rotation: np.ndarray) -> np.ndarray:
    """4x4 homogeneous transform from a translation and a 3x3 rotation."""
    t = np.eye(4)
    t[:3, :3] = rotation
    t[:3, 3] = translation
    return t


def matrix_from_pose(pose: object) -> np.ndarray:
    """4x4 transform of a geometry_msgs/Pose."""
    p, o = pose.position, pose.orientation
    return homogeneous((p.x, p.y, p.z), matrix_from_quaternion((o.x, o.y, o.z, o.w)))


def pose_from_matrix(matrix: np.ndarray) -> Pose:
    """geometry_msgs/Pose of a 4x4 transform."""
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = (float(v) for v in matrix[:3, 3])
    q = quaternion_from_matrix(matrix[:3, :3])
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = q
    return pose
