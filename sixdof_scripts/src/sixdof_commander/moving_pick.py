"""Picking a moving object (one a conveyor carries): `pick_moving(driver, object)`.

The object moves at a constant horizontal velocity (the simulator's twist of it, or the perception tracker's estimate in
a DetectedObject; the vertical part is not used). pick_moving opens the gripper (a suction cup's vacuum goes off unless
this client last turned it off) and chooses the interception: the earliest start of the follow path, from `lead` s ahead
on, whose every point the arm can reach (the object is met as far upstream as the arm reaches, or the moment the arm can
be there once it has entered its reach). The follow path is one Cartesian path timed to the object: the tool accelerates
from rest, `approach_distance` above the object's path, to the object's velocity while the object catches up with it
(`ramp`), descends onto it moving with it (`descend`), stays on it while the gripper closes (`close`), and lifts it
while coming to rest (`lift`). Every point of it is one inverse-kinematics solution of move_group's compute_ik (seeded
with the previous one), timed here to the object's motion. The arm runs the approach plan (to the follow path's first
point), waits there and runs the follow path as one trajectory, so that no command latency falls between them; the
approach must end `Timing.margin` s before the follow path starts, else the interception moves later. The follow path
and its timing are follow_path.py's. plan_pick_moving plans the interception and the approach for a given send time
(while the arm still finishes another motion, the approach's prefix), run_pick_moving runs them: pick_moving is both.

The gripper is the package's (ArmDriver's: its grasping information through move_group). Fingers close with
ArmDriver.gripper_close once the tool is at the grasp; the tool stays on the object for Timing's default `close`
(1 s, for the grasp fix) plus the fingers' travel from open to the object's width at their URDF velocity limit. A
suction cup goes to the centre of the object's top; its vacuum goes on as the descent begins, and the cup seals the
moment its face touches the top (SUCTION_TIMING: 0.12 s down during the 0.12 s ramp, touching the top as
its velocity matches the object's, 0.05 s on the top face, 0.12 s up, points 0.05 s apart; at the pre-grasp point
0.02 s early). Whether the object is held is the simulator's `attached_to` of it.

Failures come back by class in the result (`failure`): MISSED (the object passed before the arm could meet it, or
leaves the arm's reach before a follow path could end), NOT_GRASPED (the gripper closed without holding it: no grasp, or
no seal for a suction cup), DROPPED (held, then lost during the lift), UNREACHABLE (no grasp of the object's shape,
or no follow path the arm can run within `Timing.search` s), FAILED (an execution or gripper command failed). Misuse
raises SixdofCommanderError.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
import rospy
from moveit_msgs.msg import RobotTrajectory
from shape_msgs.msg import SolidPrimitive
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import DetectedObject

from .arm_driver import ArmDriver
from .blending import blended, end_state
from .exceptions import SixdofCommanderError
from .follow_path import SUCTION_TIMING, MovingObject, Timing, follow_path
from .grasping import ObjectGeometry, grasp_tcp_pose, object_geometry
from .straight_moves import FAILED, UNREACHABLE
from .suction import SuctionGripper

MISSED = "missed"
NOT_GRASPED = "not grasped"
DROPPED = "dropped"
# rad: the largest change of a joint between two follow-path points (0.1 s apart) that is not a jump to another branch.
MAX_JUMP = 0.4
# s: an approach that would wait longer than this at the pre-grasp point (beyond Timing.margin) tries an earlier start.
SPARE = 0.05
# Interception starts plan_approach tries at most.
APPROACH_TRIES = 4
# approach_step's answers: take this try's approach; keep it and try an earlier start; none from this try.
TAKE, EARLIER, NEXT = "take", "earlier", "next"
# (approach plan, follow start ROS time, follow times, follow joint positions)
_Motion = tuple[RobotTrajectory, float, np.ndarray, list[np.ndarray]]
__all__ = [
    "DROPPED",
    "FAILED",
    "MISSED",
    "NOT_GRASPED",
    "SUCTION_TIMING",
    "UNREACHABLE",
    "MovingObject",
    "MovingPickResult",
    "PlannedPick",
    "Timing",
    "follow_path",
    "pick_moving",
    "plan_pick_moving",
    "run_pick_moving",
]


def _default_timing(driver: ArmDriver, geometry: ObjectGeometry) -> Timing:
    """SUCTION_TIMING for a suction tool; for fingers, Timing() with the fingers' travel from open to the object's
    width at their URDF velocity limit added to `close` (they reach the object after it, then the grasp fix needs its
    updates)."""
    if driver.suction:
        return SUCTION_TIMING
    width = grasp_tcp_pose(geometry, driver.grasp_spec)[1]
    return Timing(close=Timing.close + driver.gripper_closing_time(width))


@dataclass
class MovingPickResult:
    """The outcome: failure '' on success, else its class (MISSED, NOT_GRASPED, DROPPED, UNREACHABLE, FAILED)."""

    object: str
    failure: str = ""
    message: str = ""
    grasp_time: float = math.nan  # ROS time the gripper closed on the object (a suction cup's vacuum went on)
    moved: bool = False  # whether the arm moved (its approach began; not on a failure found before)

    @property
    def ok(self) -> bool:
        return not self.failure


def approach_step(spare: float, kept: bool, last: bool) -> str:
    """plan_approach's rule for one try. `spare`: how long its approach would wait at the pre-grasp point beyond
    Timing.margin (negative: it arrives too late; -inf: no interception); `kept`: an earlier try's approach fits with
    more than SPARE s to spare and this try is the earlier start; `last`: no try follows. An approach that fits is
    taken when it has at most SPARE s to spare, is the earlier start or the last try (TAKE); one with more is kept
    while an earlier start is tried (EARLIER). A try without one (NEXT) falls back to the kept approach while it still
    fits, else the next try starts later."""
    if spare < 0.0:
        return NEXT
    return TAKE if kept or last or spare <= SPARE else EARLIER


def joined(approach: RobotTrajectory, times: np.ndarray, positions: list[np.ndarray]) -> RobotTrajectory:
    """The approach plan, then the follow path's positions at `times` (from the approach's start, the first after the
    approach's end): the arm waits at the approach's last state until the follow path begins there. The follow
    path's velocities by central differences, zero at both of its ends."""
    trajectory = RobotTrajectory()
    trajectory.joint_trajectory.joint_names = list(approach.joint_trajectory.joint_names)
    trajectory.joint_trajectory.points = list(approach.joint_trajectory.points)
    q = np.asarray(positions)
    velocities = np.zeros_like(q)
    velocities[1:-1] = (q[2:] - q[:-2]) / (times[2:] - times[:-2])[:, None]
    for point in trajectory.joint_trajectory.points:
        point.accelerations = []  # the follow path has none: a cubic spline through positions and velocities
    for t, p, v in zip(times, q, velocities, strict=True):
        trajectory.joint_trajectory.points.append(
            JointTrajectoryPoint(positions=list(p), velocities=list(v), time_from_start=rospy.Duration.from_sec(t))
        )
    return trajectory


class _Failed(Exception):  # noqa: N818 (internal: ends a pick with its failure class)
    def __init__(self, failure: str, message: str) -> None:
        super().__init__(message)
        self.failure = failure


class _MovingPick:
    def __init__(self, driver: ArmDriver, target: MovingObject, timing: Timing | None) -> None:
        self.driver, self.target = driver, target
        self.arm = driver.arm
        self.moved = False
        # A conveyor moves objects horizontally: the vertical part of a velocity (a fresh object settling, bouncing)
        # would be extrapolated into the belt.
        self.velocity = np.array([target.velocity[0], target.velocity[1], 0.0])
        geometry = object_geometry(target.pose, target.shape)
        self.height = geometry.height
        try:
            self.grasp0 = driver.grasp_tip(geometry)  # the tip's grasp pose over the object at its stamp
            self.timing = timing or _default_timing(driver, geometry)
        except SixdofCommanderError as err:
            raise _Failed(UNREACHABLE, f"no top-down grasp: {err}") from err
        self.joint_names = self.arm.get_active_joints()

    def grasp_at(self, t: float) -> np.ndarray:
        """The tip's grasp pose over the object at ROS time t."""
        pose = self.grasp0.copy()
        pose[:3, 3] += self.velocity * (t - self.target.stamp)
        return pose

    def poses(self, start: float) -> tuple[np.ndarray, list[np.ndarray]]:
        """The follow path (times from its start, tip poses) when it starts at ROS time `start`."""
        return follow_path(
            lambda tau: self.grasp_at(start + tau), self.velocity, self.driver.approach_distance, self.timing
        )

    def ik(self, pose: np.ndarray, seed: np.ndarray) -> np.ndarray | None:
        """One IK solution of the tip pose near `seed`, None when there is none. Collisions are not checked: the tool
        meets the object, and the belt under it."""
        return self.driver.tip_ik(pose, seed, avoid_collisions=False)

    def follow(self, start: float, seed: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]] | str:
        """(times, joint positions) of the follow path starting at ROS time `start`, each point one IK solution
        seeded with the previous one; or why there is none."""
        times, poses = self.poses(start)
        first = self.ik(poses[0], seed)
        if first is None:
            return "no IK solution at its start"
        positions = [first]
        for k, pose in enumerate(poses[1:], start=1):
            q = self.ik(pose, positions[-1])
            where = f"point {k}/{len(poses) - 1} ({pose[0, 3]:.3f}, {pose[1, 3]:.3f}, {pose[2, 3]:.3f})"
            if q is None:
                return f"no IK solution at its {where}"
            jump = float(np.max(np.abs(q - positions[-1])))
            if jump > MAX_JUMP:
                return f"its IK jumps {jump:.2f} rad at its {where}"
            positions.append(q)
        return times, positions

    def home_seed(self, seed: np.ndarray) -> np.ndarray:
        """The arm's home state (the SRDF's, ArmDriver.home_joints) in the active joints' order; `seed`'s value for a
        joint it does not name."""
        home = self.driver.home_joints
        return np.array([home.get(name, value) for name, value in zip(self.joint_names, seed, strict=True)])

    def intercept(self, earliest: float, seed: np.ndarray) -> tuple[float, np.ndarray, list[np.ndarray]]:
        """The earliest follow start from ROS time `earliest` on (in steps of `Timing.search_step`) whose whole path
        the arm can follow: (start, times, joint positions). MISSED once the path's end has left the arm's reach
        downstream while its start is reachable (the object passed), UNREACHABLE when no start within
        `Timing.search` s works. The path's start is solved seeded with `seed`, or with the home state when that
        finds no solution (from a seed far from the belt, the arm above a box's far corner, the solver can fail on
        poses the arm reaches), and its end seeded with its start's solution."""
        timing, why = self.timing, ""
        start = earliest
        seeds = (seed, self.home_seed(seed))
        while start <= earliest + timing.search:
            _, poses = self.poses(start)
            used, head = seeds[-1], None  # the seed that solved the start seeds the follow path
            for candidate in seeds:
                head = self.ik(poses[0], candidate)
                if head is not None:
                    used = candidate
                    break
            tail = self.ik(poses[-1], used if head is None else head)
            if head is not None and tail is None:
                break  # reachable at the start, not at the end: the window has passed
            if head is not None and tail is not None:
                path = self.follow(start, used)
                if not isinstance(path, str):
                    return start, path[0], path[1]
                why = f"the follow path from {start - rospy.get_time():.2f} s on: {path}"
            start += timing.search_step
        if head is not None and tail is None:
            raise _Failed(MISSED, f"the object leaves the arm's reach before a follow path ends ({why or 'no path'})")
        raise _Failed(UNREACHABLE, f"no follow path the arm can run within {timing.search:g} s ({why or 'no IK'})")

    def plan_approach(self, lead: float, prefix: RobotTrajectory | None, ready: float) -> _Motion:
        """(approach plan, follow start time, follow times, follow joint positions): the earliest interception the
        arm can be at the pre-grasp point for, `Timing.margin` s early, when the approach is sent at ROS time `ready`
        (or when computed, if later); later when the approach takes longer, earlier when it would wait more than
        SPARE s beyond that (approach_step's rule). With a prefix (a motion from the current state, or from where the
        arm will be at `ready`), the approach is planned from its end and blended with it."""
        if prefix is None:
            seed = np.asarray(self.arm.get_current_joint_values(), dtype=float)
        else:
            names = list(prefix.joint_trajectory.joint_names)
            last = prefix.joint_trajectory.points[-1].positions
            seed = np.array([last[names.index(name)] for name in self.joint_names], dtype=float)
        start = max(rospy.get_time(), ready) + lead
        tries: list[str] = []
        kept = None  # (plan, start, times, positions) of an approach that fits, while an earlier start is tried
        for attempt in range(APPROACH_TRIES):
            began = rospy.get_time()
            failure = None
            try:
                start, times, positions = self.intercept(start, seed)
            except _Failed as failed:
                failure, spare = failed, -math.inf
            else:
                plan = self.plan_to(positions[0], prefix)
                computed = rospy.get_time() - began
                now = max(rospy.get_time(), ready)  # when the approach would be sent
                duration = plan.joint_trajectory.points[-1].time_from_start.to_sec()
                tries.append(f"approach {duration:.2f} s, computed in {computed:.2f} s, {start - now:.2f} s ahead")
                spare = start - (now + duration + self.timing.margin)
            step = approach_step(spare, kept is not None, attempt == APPROACH_TRIES - 1)
            if step == TAKE:
                return plan, start, times, positions
            if step == EARLIER:
                # A later interception can need a shorter approach (nearer the box): the arm would wait out the spare
                # time at the pre-grasp point. An earlier start, SPARE s after this approach would end, is tried.
                kept = (plan, start, times, positions)
                start = max(rospy.get_time() + computed, ready) + duration + self.timing.margin + SPARE
                continue
            if kept is not None and self.fits_still(kept[0], kept[1], ready):
                return kept
            kept = None
            if failure is not None:
                raise failure
            # The next try takes about as long as this one did, and a later interception may need a longer approach:
            # the earliest start the arm can make first, then more.
            start = max(rospy.get_time() + computed, ready) + (1.0 if attempt == 0 else 1.2) * duration
            start += self.timing.margin
        raise _Failed(MISSED, f"the arm cannot get ahead of the object ({'; '.join(tries)})")

    def fits_still(self, approach: RobotTrajectory, start: float, ready: float) -> bool:
        """Whether the approach, sent now or at `ready` if later, ends `Timing.margin` s before the follow path starts
        at ROS time `start`."""
        duration = approach.joint_trajectory.points[-1].time_from_start.to_sec()
        return max(rospy.get_time(), ready) + duration + self.timing.margin <= start

    def plan_to(self, pregrasp: np.ndarray, prefix: RobotTrajectory | None) -> RobotTrajectory:
        """A plan to the pre-grasp joint positions from the current state, or the prefix and a plan from its end
        as one blended motion."""
        arm, driver = self.arm, self.driver
        try:
            if prefix is None:
                arm.set_start_state_to_current_state()
            else:
                arm.set_start_state(end_state(prefix))
            arm.set_joint_value_target(dict(zip(self.joint_names, map(float, pregrasp), strict=True)))
            ok, plan, _, _ = arm.plan()
        finally:
            arm.set_start_state_to_current_state()
        if not ok:
            raise _Failed(FAILED, f"planning to the pre-grasp point failed: {arm.last_error}")
        if prefix is None:
            return plan
        try:
            return blended(driver, [prefix, plan])
        except SixdofCommanderError as err:
            raise _Failed(FAILED, f"blending the approach: {err}") from err

    def attached(self) -> bool:
        return bool(self.driver.get_object_state(self.target.name).attached_to)

    def grip(self, start: float) -> tuple[float, str]:
        """Close the fingers when the tool is at the grasp, or turn a suction cup's vacuum on as the descent begins
        (it seals when the cup's face touches the top): (the ROS time of the command, why it failed or '')."""
        driver = self.driver
        suction = isinstance(driver.gripper, SuctionGripper)
        at = start + (self.timing.ramp - self.timing.overlap if suction else self.timing.grasp_time)
        rospy.sleep(max(at - rospy.get_time(), 0.0))
        grip_time = rospy.get_time()
        if suction:
            on = driver.gripper.grasp().reached_goal
            return grip_time, "" if on else f"the vacuum did not go on: {driver.gripper.last_status_text}"
        return grip_time, "" if driver.gripper_close() else driver.last_failure

    def open_gripper(self) -> None:
        """Open the gripper (a suction cup's vacuum off unless this client last turned it off)."""
        off = isinstance(self.driver.gripper, SuctionGripper) and self.driver.gripper.vacuum is False
        if not off and not self.driver.gripper_open():
            raise _Failed(FAILED, self.driver.last_failure)

    def run(self, motion: _Motion, opened: bool) -> float:
        """Pick along the planned motion (plan_approach's), opening the gripper first unless `opened`; the ROS time
        the gripper closed. _Failed says why not."""
        if not opened:
            self.open_gripper()
        plan, start, times, positions = motion
        # One trajectory: the approach, a wait at the pre-grasp point, the follow path timed to the object.
        offset = start - rospy.get_time()
        if offset < plan.joint_trajectory.points[-1].time_from_start.to_sec():
            raise _Failed(MISSED, f"the approach would reach the pre-grasp point {-offset:.2f} s after the object")
        trajectory = joined(plan, times + offset, positions)
        executed: list[bool] = []
        runner = threading.Thread(target=lambda: executed.append(self.arm.execute(trajectory, wait=True)))
        runner.start()
        self.moved = True
        grasp_time, why_not = self.grip(start)
        # The grasp fix attaches a squeezed object within a few of its updates, a cup the moment it touches the top:
        # until then, or the lift's end.
        lifted = start + self.timing.total
        held = not why_not and self.attached()
        while not why_not and not held and rospy.get_time() < lifted and not rospy.is_shutdown():
            rospy.sleep(0.02)
            held = self.attached()
        runner.join()
        if not executed or not executed[0]:
            raise _Failed(FAILED, f"the approach and follow path failed: {self.arm.last_error}")
        if not held:
            tool = "the suction cup sealed on nothing" if self.driver.suction else "the gripper closed"
            raise _Failed(NOT_GRASPED, why_not or f"{tool} but holds nothing")
        if not self.attached():
            raise _Failed(DROPPED, "held after closing, lost during the lift")
        round_ = self.target.shape.type == SolidPrimitive.SPHERE
        if not self.driver.hold(self.target.name, self.height, round_):
            raise _Failed(FAILED, self.driver.last_failure)
        return grasp_time


@dataclass
class PlannedPick:
    """A moving pick planned ahead (plan_pick_moving), for run_pick_moving; `result` holds its failure if planning
    failed."""

    result: MovingPickResult
    picker: _MovingPick | None = None
    motion: _Motion | None = None
    opened: bool = False  # whether the gripper was opened before planning

    def fits(self) -> bool:
        """Whether its approach, sent now, still reaches the pre-grasp point `Timing.margin` s before the object."""
        return self.motion is not None and self.picker.fits_still(self.motion[0], self.motion[1], 0.0)


def plan_pick_moving(
    driver: ArmDriver,
    target: str | MovingObject | DetectedObject,
    timing: Timing | None = None,
    lead: float = 1.3,
    prefix: RobotTrajectory | None = None,
    ready: float = 0.0,
) -> PlannedPick:
    """The interception and the approach of pick_moving (its arguments), planned to be sent at ROS time `ready` (or
    as soon as planned, if later): while the arm still runs another motion (the place before; the prefix then starts
    where that motion ends). The gripper opens first when `ready` is not ahead (else run_pick_moving opens it, and a
    suction cup's vacuum this client turned off stays off); nothing else moves: run_pick_moving runs it."""
    if not isinstance(driver, ArmDriver):
        raise SixdofCommanderError(f"pick_moving needs an ArmDriver, got {type(driver).__name__}")
    if isinstance(target, str):
        target = MovingObject.from_simulator(driver, target)
    elif isinstance(target, DetectedObject):
        target = MovingObject.from_detection(target)
    elif not isinstance(target, MovingObject):
        raise SixdofCommanderError(f"pick_moving target must be a name, MovingObject or DetectedObject, got {target!r}")
    if isinstance(lead, bool) or not isinstance(lead, int | float) or not math.isfinite(lead) or lead <= 0.0:
        raise SixdofCommanderError(f"pick_moving lead must be a number > 0, got {lead!r}")
    planned = PlannedPick(MovingPickResult(target.name))
    try:
        planned.picker = _MovingPick(driver, target, timing)
        if ready <= rospy.get_time():
            planned.picker.open_gripper()
            planned.opened = True
        planned.motion = planned.picker.plan_approach(float(lead), prefix, ready)
    except _Failed as failed:
        planned.result.failure, planned.result.message = failed.failure, f"pick_moving '{target.name}': {failed}"
        rospy.logerr(planned.result.message)
    return planned


def run_pick_moving(planned: PlannedPick) -> MovingPickResult:
    """Run a pick plan_pick_moving planned (its failure, if it has one): the approach is sent now, MISSED when it can
    no longer reach the pre-grasp point before the object."""
    result = planned.result
    if result.failure:
        return result
    try:
        result.grasp_time = planned.picker.run(planned.motion, planned.opened)
    except _Failed as failed:
        result.failure, result.message = failed.failure, f"pick_moving '{result.object}': {failed}"
        rospy.logerr(result.message)
    result.moved = planned.picker.moved
    return result


def pick_moving(
    driver: ArmDriver,
    target: str | MovingObject | DetectedObject,
    timing: Timing | None = None,
    lead: float = 1.3,
    prefix: RobotTrajectory | None = None,
) -> MovingPickResult:
    """Grasp a moving object on the fly and lift it (module docstring). target: a simulator object's name (its
    pose and velocity from the simulator), a MovingObject, or a DetectedObject with a tracked velocity. The follow path
    starts at the earliest `lead` s from now (later when the object is not yet in reach or the approach needs
    longer). timing: SUCTION_TIMING for a suction tool, for fingers Timing() with their closing time added to `close`
    (module docstring) unless given. prefix: a motion from the arm's current state (e.g. the retreat from a place) the
    approach continues without stopping at its end. On success the driver holds the object (ArmDriver.place puts it
    down). plan_pick_moving and run_pick_moving are its two halves."""
    return run_pick_moving(plan_pick_moving(driver, target, timing, lead, prefix))
