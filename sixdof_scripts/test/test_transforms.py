"""The commander's adapters of scipy's Rotation keep tf2's conventions: setRPY / getRPY (tf.transformations
'sxyz'), quaternions (x, y, z, w) with w >= 0 from matrices, the angle between two rotations."""

import math
import random

import numpy as np
import pytest
from sixdof_commander.transforms import (
    matrix_from_quaternion,
    quaternion_from_matrix,
    quaternion_from_rpy,
    rotation_angle,
    rpy_from_quaternion,
)


def rx(a):
    return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])


def ry(a):
    return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])


def rz(a):
    return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])


def same_rotation(q1, q2, tol=1e-9):
    return abs(abs(float(np.dot(q1, q2))) - 1.0) < tol


def random_rpy(rng):
    return (rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi / 2, math.pi / 2), rng.uniform(-math.pi, math.pi))


@pytest.mark.parametrize(
    ("rpy", "expected"),
    [
        ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)),
        ((math.pi / 2, 0.0, 0.0), (math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5))),
        ((0.0, math.pi / 2, 0.0), (0.0, math.sqrt(0.5), 0.0, math.sqrt(0.5))),
        ((0.0, 0.0, math.pi / 2), (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))),
        ((math.pi, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0)),
        # tf.transformations.quaternion_from_euler(0.1, 0.2, 0.3) (axes 'sxyz', the default)
        ((0.1, 0.2, 0.3), (0.034270798550482096, 0.10602051106179562, 0.14357217502739282, 0.9833474432563558)),
    ],
)
def test_known_quaternions(rpy, expected):
    assert quaternion_from_rpy(*rpy) == pytest.approx(expected, abs=1e-12)


def test_fixed_axes_composition_rz_ry_rx():
    rng = random.Random(7)
    for _ in range(200):
        r, p, y = random_rpy(rng)
        m = matrix_from_quaternion(quaternion_from_rpy(r, p, y))
        np.testing.assert_allclose(m, rz(y) @ ry(p) @ rx(r), atol=1e-12)


def test_rpy_round_trip_and_pykdl_get_rpy():
    rng = random.Random(13)
    for _ in range(200):
        rpy = random_rpy(rng)
        q = quaternion_from_rpy(*rpy)
        assert rpy_from_quaternion(q) == pytest.approx(rpy, abs=1e-9)


def test_rpy_at_gimbal_lock_reproduces_the_rotation_with_yaw_zero(recwarn):
    for pitch in (math.pi / 2, -math.pi / 2):
        q = quaternion_from_rpy(0.3, pitch, -0.2)
        back = rpy_from_quaternion(q)
        assert back[1] == pytest.approx(pitch)
        assert back[2] == 0.0
        assert same_rotation(quaternion_from_rpy(*back), q)
    assert not recwarn.list


def test_paper_home_pose_points_the_tool_down():
    q = quaternion_from_rpy(*(math.radians(a) for a in (-180.0, 0.688, 179.995)))
    z_axis = matrix_from_quaternion(q)[:, 2]
    assert z_axis[2] == pytest.approx(-1.0, abs=1e-3)


def test_quaternion_from_matrix_round_trip_every_branch():
    rng = random.Random(17)
    cases = [quaternion_from_rpy(*random_rpy(rng)) for _ in range(200)]
    # Near-180-degree rotations exercise the diagonal branches.
    cases += [
        quaternion_from_rpy(math.pi, 0, 0),
        quaternion_from_rpy(0, math.pi, 0),
        quaternion_from_rpy(0, 0, math.pi),
    ]
    for q in cases:
        back = quaternion_from_matrix(matrix_from_quaternion(q))
        assert back[3] >= 0.0
        assert same_rotation(back, q)


def test_rotation_angle():
    q = quaternion_from_rpy(0.1, -0.2, 0.3)
    assert rotation_angle(q, q) == pytest.approx(0.0, abs=1e-7)
    assert rotation_angle(q, [-c for c in q]) == pytest.approx(0.0, abs=1e-7)
    turned = matrix_from_quaternion(q) @ rz(0.4)
    assert rotation_angle(q, quaternion_from_matrix(turned)) == pytest.approx(0.4)
    assert rotation_angle((0, 0, 0, 1), (1, 0, 0, 0)) == pytest.approx(math.pi)
    with pytest.raises(ValueError, match="zero norm"):
        rotation_angle((0, 0, 0, 0), q)
