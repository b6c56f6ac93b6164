"""Placement error and tilt."""

import math

import pytest
from geometry_msgs.msg import Pose

from sixdof_bringup.placement import placement, tilt_angle


def pose_rotated_about_x(angle: float, x=0.0, y=0.0, z=0.0) -> Pose:
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.x, p.orientation.w = math.sin(angle / 2.0), math.cos(angle / 2.0)
    return p


def test_upright_and_yawed_objects_have_no_tilt():
    yawed = Pose()
    yawed.orientation.z, yawed.orientation.w = math.sin(0.6), math.cos(0.6)
    assert tilt_angle(yawed) == pytest.approx(0.0, abs=1e-9)
    assert tilt_angle(pose_rotated_about_x(0.2)) == pytest.approx(0.2)
    assert tilt_angle(pose_rotated_about_x(math.pi)) == pytest.approx(math.pi)


def test_placement_error_is_the_centre_distance():
    result = placement(pose_rotated_about_x(0.0, 0.403, 0.196, 0.02), (0.40, 0.20, 0.02))
    assert result.error == pytest.approx(0.005)
    assert result.tilt == pytest.approx(0.0)


def test_zero_quaternion_is_rejected():
    bad = Pose()
    with pytest.raises(ValueError, match="zero quaternion"):
        tilt_angle(bad)
