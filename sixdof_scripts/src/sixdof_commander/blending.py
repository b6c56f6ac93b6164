"""Joining arm motions without stops: the joint paths of consecutive motions (a plan, then a Cartesian path from its
end, ...) as one path, timed once by move_group's time-optimal parameterization (retime_trajectory).

That parameterization cuts a corner by at most 0.01 rad, so at a sharp one (a straight descent after a transit, a
plan after a straight retreat) the arm all but stops. Each corner is therefore rounded first: the last part of one
motion and the first part of the next, each up to half its motion's length and at most CORNER rad long, are replaced
by a quadratic Bezier curve in joint space through the corner's neighbourhood (tangent to both motions where it
meets them), every state of which move_group's check_state_validity finds collision-free (else a tighter curve is
tried, down to WAYPOINT_SPACING; failing all, the corner stays).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from moveit_msgs.msg import RobotState, RobotTrajectory
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

from .arm_driver import ArmDriver
from .exceptions import SixdofCommanderError

# rad (joint-space norm) between the waypoints blended: the motions' points closer than this are left out. Their
# timed points lie milliseconds apart near each rest; the parameterization's blends are at most half a segment long,
# so corners between such tiny segments would be passed at a crawl.
WAYPOINT_SPACING = 0.02
# rad (joint-space arc length): the most of each motion a rounded corner replaces.
CORNER = 0.3
__all__ = ["CORNER", "WAYPOINT_SPACING", "blended", "end_state", "round_corner"]


def end_state(trajectory: RobotTrajectory) -> RobotState:
    """The state where `trajectory` ends."""
    points = trajectory.joint_trajectory
    return RobotState(joint_state=JointState(name=list(points.joint_names), position=list(points.points[-1].positions)))


def _along(path: np.ndarray, distance: float) -> tuple[int, np.ndarray]:
    """The point `distance` (rad of arc length) along the path, and the index of the first point beyond it."""
    for i in range(1, len(path)):
        step = float(np.linalg.norm(path[i] - path[i - 1]))
        if step >= distance:
            return i, path[i - 1] + (path[i] - path[i - 1]) * (distance / step if step > 0.0 else 0.0)
        distance -= step
    return len(path), path[-1]


def _length(path: np.ndarray) -> float:
    return float(np.sum(np.linalg.norm(np.diff(path, axis=0), axis=1)))


def round_corner(a: np.ndarray, b: np.ndarray, valid: Callable[[np.ndarray], bool]) -> np.ndarray:
    """Joint path a (points x joints) then path b (starting where a ends), the corner between them rounded (module
    docstring) when every state of the curve is valid(state). The widest curve is tried first, then ones half as
    wide, down to WAYPOINT_SPACING: beside an obstacle (a held object over the box's wall) a tighter curve can be
    valid where a wide one is not."""
    reach = min(CORNER, _length(a) / 2.0, _length(b) / 2.0)
    while reach >= WAYPOINT_SPACING:
        cut_a, p0 = _along(a[::-1], reach)
        cut_b, p2 = _along(b, reach)
        count = max(2, math.ceil(2.0 * reach / WAYPOINT_SPACING))
        t = np.linspace(0.0, 1.0, count + 1)[:, None]
        curve = (1.0 - t) ** 2 * p0 + 2.0 * t * (1.0 - t) * a[-1] + t**2 * p2
        if all(valid(q) for q in curve[1:-1]):
            path = np.vstack([a[: len(a) - cut_a], curve, b[cut_b:]])
            return path[np.r_[True, np.linalg.norm(np.diff(path, axis=0), axis=1) > 1e-12]]  # no repeated points
        reach /= 2.0
    return np.vstack([a, b[1:]])


def blended(driver: ArmDriver, parts: list[RobotTrajectory]) -> RobotTrajectory:
    """One trajectory through the positions of `parts` (each starting where the previous one ends, all of the same
    joints), its corners rounded (module docstring) and its points WAYPOINT_SPACING apart, from rest to rest,
    time-optimal within the joint limits times the arm's scaling factors. A failure raises SixdofCommanderError."""
    names = list(parts[0].joint_trajectory.joint_names)
    if any(list(part.joint_trajectory.joint_names) != names for part in parts):
        raise SixdofCommanderError("blended: the motions do not move the same joints")
    path = np.array([p.positions for p in parts[0].joint_trajectory.points], dtype=float)
    for part in parts[1:]:
        following = np.array([p.positions for p in part.joint_trajectory.points], dtype=float)
        path = round_corner(path, following, lambda q: driver.state_valid(names, q))
    kept = [path[0]]
    for q in path[1:-1]:
        if np.linalg.norm(q - kept[-1]) >= WAYPOINT_SPACING:
            kept.append(q)
    if len(kept) > 1 and np.linalg.norm(path[-1] - kept[-1]) < WAYPOINT_SPACING:
        kept.pop()  # no tiny last segment: the path ends exactly where the last part ends
    kept.append(path[-1])
    joined = RobotTrajectory()
    joined.joint_trajectory.joint_names = names
    joined.joint_trajectory.points = [JointTrajectoryPoint(positions=list(map(float, q))) for q in kept]
    return driver.arm.retime_trajectory(
        RobotState(),
        joined,
        driver.arm.get_max_velocity_scaling_factor(),
        driver.arm.get_max_acceleration_scaling_factor(),
        algorithm="time_optimal_trajectory_generation",
    )
