"""The follow path of a moving pick (moving_pick.pick_moving): the object moving at a constant velocity
(`MovingObject`), the durations of the path's phases (`Timing`, `SUCTION_TIMING` for a suction cup) and the tip poses
of the path timed to the object (`follow_path`, pure geometry).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import rospy
from shape_msgs.msg import SolidPrimitive

from sixdof_msgs.msg import DetectedObject

from .arm_driver import ArmDriver
from .exceptions import SixdofCommanderError
from .grasping import raised
from .transforms import matrix_from_pose

__all__ = ["SUCTION_TIMING", "MovingObject", "Timing", "follow_path"]


@dataclass(frozen=True)
class MovingObject:
    """An object moving at a constant velocity: its pose (4x4, planning frame) at `stamp` (ROS time, s)."""

    name: str
    pose: np.ndarray
    velocity: np.ndarray  # m/s, planning frame
    stamp: float
    shape: SolidPrimitive

    def at(self, t: float) -> np.ndarray:
        """The predicted pose at ROS time t."""
        pose = self.pose.copy()
        pose[:3, 3] += self.velocity * (t - self.stamp)
        return pose

    @classmethod
    def from_simulator(cls, driver: ArmDriver, name: str) -> MovingObject:
        """The simulator's pose and linear velocity of the object now."""
        state = driver.get_object_state(name)
        v = state.twist.linear
        return cls(
            name, matrix_from_pose(state.object.pose), np.array([v.x, v.y, v.z]), rospy.get_time(), state.object.shape
        )

    @classmethod
    def from_detection(cls, detection: DetectedObject) -> MovingObject:
        """A perception detection with its tracked velocity (SixdofCommanderError when it has none yet)."""
        if not detection.velocity_valid:
            raise SixdofCommanderError(f"detected object '{detection.id}' has no velocity estimate yet")
        v = detection.velocity
        return cls(
            detection.id,
            matrix_from_pose(detection.pose.pose),
            np.array([v.x, v.y, v.z]),
            detection.pose.header.stamp.to_sec(),
            detection.shape,
        )


@dataclass(frozen=True)
class Timing:
    """Durations (s) of the follow path's phases, its point spacing, how early the arm waits at the pre-grasp point,
    and how far ahead (in which steps) the interception is searched for. overlap: s of the descent within the end of
    the ramp (0 to the shorter of the two): the tool comes down while it still catches up with the object, and meets
    it `descend - overlap` s after matching its velocity (at the ramp's end when overlap is descend)."""

    ramp: float = 0.2
    descend: float = 0.3
    close: float = 1.0
    lift: float = 0.3
    step: float = 0.1
    margin: float = 0.2
    search: float = 4.0
    search_step: float = 0.1
    overlap: float = 0.0

    def __post_init__(self) -> None:
        for name in ("ramp", "descend", "close", "lift", "step", "margin", "search", "search_step", "overlap"):
            value = getattr(self, name)
            number = not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value)
            if not number or value < 0 or (value == 0 and name != "overlap"):
                bound = ">= 0" if name == "overlap" else "> 0"
                raise SixdofCommanderError(f"pick_moving timing '{name}' must be a number {bound}, got {value!r}")
        if self.overlap > min(self.ramp, self.descend):
            raise SixdofCommanderError(f"pick_moving timing 'overlap' {self.overlap:g} s exceeds the ramp or descent")

    @property
    def grasp_time(self) -> float:
        """From the follow start to the moment the tool is at the grasp (the gripper closes then)."""
        return self.ramp - self.overlap + self.descend

    @property
    def total(self) -> float:
        return self.grasp_time + self.close + self.lift


# A suction cup seals as it touches the top (its vacuum already on): a short stay on the top face instead of a close,
# and a quicker descent and lift (nothing closes around the object: it need not be met as gently), the descent within
# the ramp (the cup is above the top until it touches it, as its velocity matches the object's).
SUCTION_TIMING = Timing(
    ramp=0.12, descend=0.12, close=0.05, lift=0.12, step=0.05, margin=0.02, search_step=0.05, overlap=0.12
)


def follow_path(
    grasp_at: Callable[[float], np.ndarray], velocity: np.ndarray, height: float, timing: Timing
) -> tuple[np.ndarray, list[np.ndarray]]:
    """(times from the follow start, tip poses) of the follow path. grasp_at(tau): the tip's grasp pose over the
    object tau seconds after the start. The tool starts at rest `height` above grasp_at(ramp / 2) and accelerates
    uniformly to `velocity`, which puts it above grasp_at(tau) from tau = ramp on; it descends (half a cosine) to the
    grasp and stays there for `close`, then rises back by `height` while decelerating uniformly to rest (the object,
    held, has left the belt)."""
    ramp, end_close = timing.ramp, timing.grasp_time + timing.close
    start = grasp_at(ramp / 2.0)
    count = int(math.ceil(timing.total / timing.step - 1e-9))
    times = np.linspace(0.0, timing.total, count + 1)
    poses = []
    for tau in times:
        if tau <= ramp:
            travel = tau * tau / (2.0 * ramp)
        elif tau <= end_close:
            travel = tau - ramp / 2.0
        else:
            after = min(tau - end_close, timing.lift)
            travel = end_close - ramp / 2.0 + after - after * after / (2.0 * timing.lift)
        down = tau - (ramp - timing.overlap)
        if down <= 0.0:
            z = height
        elif down <= timing.descend:
            z = height * (1.0 + math.cos(math.pi * down / timing.descend)) / 2.0
        elif down <= timing.descend + timing.close:
            z = 0.0
        elif down <= timing.descend + timing.close + timing.lift:
            up = down - timing.descend - timing.close
            z = height * (1.0 - math.cos(math.pi * up / timing.lift)) / 2.0
        else:
            z = height
        pose = start.copy()
        pose[:3, 3] += np.asarray(velocity) * travel
        poses.append(raised(pose, z))
    return times, poses
