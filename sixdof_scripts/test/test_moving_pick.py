"""The follow path of pick_moving: at rest at both ends, over the object (matching its velocity) from the end of the
ramp until the gripper has closed, down on it while it closes; the timing's checks; the approach's rule; the
interception's IK seeds."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from sixdof_commander import SixdofCommanderError
from sixdof_commander.moving_pick import (
    EARLIER,
    NEXT,
    SPARE,
    SUCTION_TIMING,
    TAKE,
    UNREACHABLE,
    Timing,
    _Failed,
    _MovingPick,
    approach_step,
    follow_path,
)
from sixdof_commander.transforms import homogeneous


def test_follow_path_meets_the_object_and_matches_its_velocity():
    velocity = np.array([0.0, 0.2, 0.0])
    grasp0 = homogeneous([0.45, -0.2, 0.05], np.diag([1.0, -1.0, -1.0]))

    def grasp_at(tau):
        pose = grasp0.copy()
        pose[:3, 3] += velocity * tau
        return pose

    timing = Timing(ramp=0.6, descend=1.0, close=1.5, lift=1.0, step=0.05, margin=0.5)
    times, poses = follow_path(grasp_at, velocity, 0.08, timing)
    assert len(times) == len(poses) == round(timing.total / timing.step) + 1
    assert times[0] == 0.0 and times[-1] == pytest.approx(timing.total)
    xyz = np.array([p[:3, 3] for p in poses])
    speed = np.diff(xyz, axis=0) / np.diff(times)[:, None]
    # At rest at both ends: the first and last steps' mean speeds are those of half a step into the ramps, and of the
    # last step of the lift's half cosine.
    assert np.linalg.norm(speed[0]) < 0.2 * timing.step / 2.0 / timing.ramp + 1e-9
    assert np.linalg.norm(speed[-1][:2]) < 0.2 * timing.step / 2.0 / timing.lift + 1e-9
    assert abs(speed[-1][2]) < 0.08 * (1.0 - math.cos(math.pi * timing.step / timing.lift)) / 2.0 / timing.step + 1e-9
    # The start is the approach height above where the ramp's middle meets the object.
    assert xyz[0] == pytest.approx(grasp_at(timing.ramp / 2.0)[:3, 3] + [0.0, 0.0, 0.08])
    end_close = timing.ramp + timing.descend + timing.close
    for tau, pose in zip(times, poses, strict=True):
        if timing.ramp <= tau <= end_close:
            # Over the object, at the object's speed.
            assert pose[:2, 3] == pytest.approx(grasp_at(tau)[:2, 3], abs=1e-9)
        if timing.grasp_time <= tau <= timing.grasp_time + timing.close:
            assert pose[:3, 3] == pytest.approx(grasp_at(tau)[:3, 3], abs=1e-9)  # down on it while closing
        assert pose[:3, :3] == pytest.approx(grasp0[:3, :3])
    assert xyz[:, 2].max() == pytest.approx(0.05 + 0.08)
    assert xyz[:, 2].min() == pytest.approx(0.05)
    # Matching the object's velocity on the final approach and while it closes.
    during = (times[:-1] >= timing.ramp) & (times[1:] <= end_close)
    assert speed[during][:, 1] == pytest.approx(0.2, abs=1e-9)


@pytest.mark.parametrize("name", ["ramp", "descend", "close", "lift", "step", "margin"])
def test_timing_refuses_bad_durations(name):
    for bad in (0.0, -1.0, float("nan"), True, "1"):
        with pytest.raises(SixdofCommanderError, match=name):
            Timing(**{name: bad})


def test_approach_step_takes_the_first_approach_that_fits_without_much_to_spare():
    assert approach_step(0.0, kept=False, last=False) == TAKE
    assert approach_step(SPARE, kept=False, last=False) == TAKE
    # More to spare: an earlier start is tried first, unless no try follows.
    assert approach_step(SPARE + 0.01, kept=False, last=False) == EARLIER
    assert approach_step(SPARE + 0.01, kept=False, last=True) == TAKE
    # The earlier start's approach is taken whenever it fits.
    assert approach_step(1.0, kept=True, last=False) == TAKE
    # Too late, or no interception: the next try (the kept approach first, while it still fits).
    for kept in (False, True):
        assert approach_step(-0.01, kept=kept, last=False) == NEXT
        assert approach_step(-math.inf, kept=kept, last=True) == NEXT


def test_an_overlapping_descent_touches_the_object_as_the_ramp_ends():
    velocity = np.array([0.3, 0.0, 0.0])
    grasp0 = homogeneous([0.4, 0.0, 0.05], np.diag([1.0, -1.0, -1.0]))

    def grasp_at(tau):
        pose = grasp0.copy()
        pose[:3, 3] += velocity * tau
        return pose

    timing = Timing(ramp=0.2, descend=0.12, close=0.05, lift=0.12, step=0.01, overlap=0.12)
    assert timing.grasp_time == pytest.approx(timing.ramp) and timing.total == pytest.approx(0.37)
    times, poses = follow_path(grasp_at, velocity, 0.03, timing)
    for tau, pose in zip(times, poses, strict=True):
        above = pose[2, 3] - grasp_at(tau)[2, 3]
        if tau < (timing.ramp - timing.overlap) - 1e-9:
            assert above == pytest.approx(0.03)
        elif tau < timing.ramp - 1e-9:
            assert 0.0 < above <= 0.03 + 1e-9  # coming down, still above the top
        elif tau <= timing.grasp_time + timing.close + 1e-9:
            assert pose[:3, 3] == pytest.approx(grasp_at(tau)[:3, 3], abs=1e-9)  # on it, moving with it


@pytest.mark.parametrize("overlap", [-0.1, 0.25, float("nan")])
def test_timing_refuses_a_bad_overlap(overlap):
    with pytest.raises(SixdofCommanderError, match="overlap"):
        Timing(ramp=0.2, descend=0.3, overlap=overlap)


class _SeededPick(_MovingPick):
    """An interception over two joints whose IK finds a solution only from a seed with the second joint at 1 (the
    home state's): the first joint follows the tip's y."""

    def __init__(self, home: dict[str, float]) -> None:  # no driver, arm or object: intercept's inputs only
        self.timing = SUCTION_TIMING
        self.driver = SimpleNamespace(home_joints=home)
        self.joint_names = ["a", "b"]

    def poses(self, start: float) -> tuple[np.ndarray, list[np.ndarray]]:
        return np.array([0.0, 0.1]), [homogeneous([0.4, y, 0.1], np.eye(3)) for y in (start * 0.01, start * 0.01 + 0.1)]

    def ik(self, pose: np.ndarray, seed: np.ndarray) -> np.ndarray | None:
        return np.array([pose[1, 3], 1.0]) if seed[1] == 1.0 else None


def test_the_interception_falls_back_to_the_home_state_as_its_ik_seed():
    start, times, positions = _SeededPick({"b": 1.0}).intercept(5.0, np.array([0.3, 0.0]))
    assert start == 5.0
    assert [q[1] for q in positions] == [1.0, 1.0]
    # Without a home state that seeds a solution, nothing is found: unreachable.
    with pytest.raises(_Failed) as failed:
        _SeededPick({}).intercept(5.0, np.array([0.3, 0.0]))
    assert failed.value.failure == UNREACHABLE
