"""Where an object ended up relative to a place target: position error and tilt from upright."""

from __future__ import annotations

import math
from dataclasses import dataclass

from geometry_msgs.msg import Pose


@dataclass(frozen=True)
class Placement:
    error: float  # distance of the object's centre from the target centre (m)
    tilt: float  # angle between the object's z axis and the world's z axis (rad); 0 = upright


def tilt_angle(pose: Pose) -> float:
    """Angle between the pose's z axis and +z (rad)."""
    q = pose.orientation
    norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w
    if norm2 == 0.0:
        raise ValueError("pose orientation is a zero quaternion")
    # z component of the rotated z axis: R[2][2] = 1 - 2 (x^2 + y^2) for a unit quaternion.
    zz = 1.0 - 2.0 * (q.x * q.x + q.y * q.y) / norm2
    return math.acos(max(-1.0, min(1.0, zz)))


def placement(pose: Pose, target: tuple[float, float, float]) -> Placement:
    """Position error of pose against the target centre (x, y, z) and its tilt."""
    p = pose.position
    return Placement(error=math.dist((p.x, p.y, p.z), target), tilt=tilt_angle(pose))
