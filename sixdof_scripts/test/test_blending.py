"""Rounding the corner between two joint paths (blending.round_corner): tangent to both where it meets them, within
CORNER of the corner on each, left sharp when a state of the curve is not valid."""

import numpy as np
import pytest
from sixdof_commander.blending import CORNER, WAYPOINT_SPACING, round_corner

UP = np.linspace([0.0, 0.0], [0.0, 0.2], 21)  # 0.2 rad along joint 2
OVER = np.linspace([0.0, 0.2], [1.0, 0.2], 51)  # then 1 rad along joint 1


def test_the_corner_is_rounded_within_half_the_shorter_path():
    path = round_corner(UP, OVER, lambda q: True)
    reach = min(CORNER, 0.1)
    assert path[0] == pytest.approx(UP[0]) and path[-1] == pytest.approx(OVER[-1])
    # The first half of the short path is untouched, and the curve starts where it ends, going the same way.
    start = int(np.argmax(path[:, 0] > 1e-12)) - 1
    assert path[start] == pytest.approx([0.0, 0.2 - reach])
    assert path[start + 1][1] > path[start][1]
    # It leaves out the corner itself, and meets the second path at reach along it, going its way.
    assert np.min(np.linalg.norm(path - [0.0, 0.2], axis=1)) > 0.25 * reach
    joined = int(np.argmin(np.linalg.norm(path - [reach, 0.2], axis=1)))
    assert path[joined] == pytest.approx([reach, 0.2])
    assert path[joined + 1][0] > path[joined][0] and path[joined + 1][1] == pytest.approx(0.2)
    # No step longer than the waypoint spacing, and no step backwards.
    steps = np.diff(path, axis=0)
    assert np.max(np.linalg.norm(steps, axis=1)) <= WAYPOINT_SPACING + 1e-9
    assert np.all(steps[:, 0] >= -1e-12) and np.all(steps[:, 1] >= -1e-12)


def test_an_invalid_curve_leaves_the_corner_sharp():
    path = round_corner(UP, OVER, lambda q: q[0] < 0.01 or q[1] > 0.199)
    assert path == pytest.approx(np.vstack([UP, OVER[1:]]))


def test_a_tighter_curve_is_taken_when_the_widest_is_not_valid():
    # Invalid more than 0.03 rad from the corner on joint 2: the widest curve (0.1 rad) is not, a tighter one is.
    path = round_corner(UP, OVER, lambda q: q[1] > 0.17 - 1e-9)
    assert path[0] == pytest.approx(UP[0]) and path[-1] == pytest.approx(OVER[-1])
    assert np.min(np.linalg.norm(path - [0.0, 0.2], axis=1)) > 1e-3  # the corner is cut
    assert np.min(path[np.abs(path[:, 0]) > 1e-12][:, 1]) > 0.17 - 1e-9
