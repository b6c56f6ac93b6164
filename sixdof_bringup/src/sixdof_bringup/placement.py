"""Where an object ended up relative to a place target: position error and tilt from upright."""

from __future__ import annotations

import math
from dataclasses import dataclass

from geometry_msgs.msg import Pose
from sixdof_commander.transforms import matrix_from_quaternion


@dataclass(frozen=True)
class Placement:
    error: float  # distance of the object's centre from the target centre (m)
    tilt: float  # angle between the object's z axis and the world's z axis (rad); 0 = upright


def tilt_angle(pose: Pose) -> float:
    """Angle between the pose's z axis and +z (rad)."""
    q = pose.orientation
    if q.x == q.y == q.z == q.w == 0.0:
        raise ValueError("pose orientation is a zero quaternion")
    zz = matrix_from_quaternion((q.x, q.y, q.z, q.w))[2, 2]  # z component of the rotated z axis
    return math.acos(max(-1.0, min(1.0, zz)))


def placement(pose: Pose, target: tuple[float, float, float]) -> Placement:
    """Position error of pose against the target centre (x, y, z) and its tilt."""
    p = pose.position
    return Placement(error=math.dist((p.x, p.y, p.z), target), tilt=tilt_angle(pose))
