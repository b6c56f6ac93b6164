"""Small rotation helpers (quaternions as (x, y, z, w), fixed-axis roll/pitch/yaw like tf2 setRPY)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

Quaternion = tuple[float, float, float, float]


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Quaternion (x, y, z, w) of rotations about the fixed x, y, z axes: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def matrix_from_quaternion(q: Sequence[float]) -> np.ndarray:
    """3x3 rotation matrix of a unit quaternion (x, y, z, w)."""
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def quaternion_from_matrix(m: np.ndarray) -> Quaternion:
    """Unit quaternion (x, y, z, w) with w >= 0 of a 3x3 rotation matrix."""
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    # Pick the largest diagonal term to divide by, for numerical stability.
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = (0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = ((m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s)
    norm = math.sqrt(sum(c * c for c in q))
    sign = -1.0 if q[3] < 0.0 else 1.0
    return (sign * q[0] / norm, sign * q[1] / norm, sign * q[2] / norm, sign * q[3] / norm)


def rpy_from_quaternion(q: Sequence[float]) -> tuple[float, float, float]:
    """Fixed-axis (roll, pitch, yaw) of a unit quaternion, with pitch in [-pi/2, pi/2] (tf2 getRPY)."""
    m = matrix_from_quaternion(q)
    if abs(m[2, 0]) >= 1.0 - 1e-12:
        # Gimbal lock: only roll - yaw (or roll + yaw) is defined; report yaw = 0 as tf2 does.
        if m[2, 0] < 0.0:
            return (math.atan2(m[0, 1], m[0, 2]), math.pi / 2.0, 0.0)
        return (math.atan2(-m[0, 1], -m[0, 2]), -math.pi / 2.0, 0.0)
    pitch = -math.asin(m[2, 0])
    return (math.atan2(m[2, 1], m[2, 2]), pitch, math.atan2(m[1, 0], m[0, 0]))


def matrix_from_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """3x3 rotation matrix Rz(yaw) Ry(pitch) Rx(roll)."""
    return matrix_from_quaternion(quaternion_from_rpy(roll, pitch, yaw))


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
