"""Picking a moving object (one a conveyor carries): `pick_moving(driver, object)`.

The object moves at a constant horizontal velocity (the simulator's twist of it, or the perception tracker's estimate
in a DetectedObject; the vertical part is not used). pick_moving opens the gripper, plans the arm to a pre-grasp point
`approach_distance` above where the object will be at the follow path's start: chosen so that the gripper closes
where the object passes nearest the arm's base (or as soon as the arm can be there, `Timing.margin` seconds early,
once the object has passed), and then runs one Cartesian path timed to the object: the tool accelerates from rest to
the object's velocity while the object catches up with it (`ramp`), descends onto it moving with it (`descend`),
stays on it while the gripper closes (`close`), lifts straight up still moving with it (`lift`) and comes to rest
(`ramp`). Every point of that path is one inverse-kinematics solution of move_group's compute_ik (seeded with the
previous one), timed here to the object's motion.

The gripper is the package's (ArmDriver's: its grasping information through move_group), closed with
ArmDriver.gripper_close; whether the object is held is the simulator's `attached_to` of it.

Failures come back by class in the result (`failure`): MISSED (the object passed before the arm could meet it, or
is out of the arm's reach after passing its base), NOT_GRASPED (the gripper closed without holding it: no grasp, or
no seal for a suction cup), DROPPED (held, then lost during the lift), UNREACHABLE (no grasp of the object's shape,
or no arm pose for the approach or the follow path), FAILED (an execution or gripper command failed). Misuse
raises SixdofCommanderError.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import rospy
from moveit_msgs.msg import MoveItErrorCodes, RobotTrajectory
from moveit_msgs.srv import GetPositionIK, GetPositionIKRequest
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import DetectedObject

from ._ros import SERVICE_TIMEOUT, PersistentService, call_service, resolve
from .arm_driver import FAILED, UNREACHABLE, ArmDriver, pose_from_matrix
from .exceptions import SixdofCommanderError
from .grasping import grasp_tcp_pose, object_geometry, raised, tip_pose
from .transforms import matrix_from_pose

MISSED = "missed"
NOT_GRASPED = "not grasped"
DROPPED = "dropped"
# rad: the largest change of a joint between two follow-path points (50 ms apart) that is not a jump to another branch.
MAX_JUMP = 0.3
__all__ = [
    "DROPPED",
    "FAILED",
    "MISSED",
    "NOT_GRASPED",
    "UNREACHABLE",
    "MovingObject",
    "MovingPickResult",
    "Timing",
    "follow_path",
    "pick_moving",
]


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
    """Durations (s) of the follow path's phases, its point spacing, and how early the arm waits at the pre-grasp."""

    ramp: float = 0.4
    descend: float = 0.6
    close: float = 1.0
    lift: float = 0.6
    step: float = 0.05
    margin: float = 0.3

    def __post_init__(self) -> None:
        for name in ("ramp", "descend", "close", "lift", "step", "margin"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value <= 0:
                raise SixdofCommanderError(f"pick_moving timing '{name}' must be a number > 0, got {value!r}")

    @property
    def grasp_time(self) -> float:
        """From the follow start to the moment the tool is at the grasp (the gripper closes then)."""
        return self.ramp + self.descend

    @property
    def total(self) -> float:
        return 2.0 * self.ramp + self.descend + self.close + self.lift


@dataclass
class MovingPickResult:
    """The outcome: failure '' on success, else its class (MISSED, NOT_GRASPED, DROPPED, UNREACHABLE, FAILED)."""

    object: str
    failure: str = ""
    message: str = ""
    grasp_time: float = math.nan  # ROS time the gripper closed on the object

    @property
    def ok(self) -> bool:
        return not self.failure


def follow_path(
    grasp_at: Callable[[float], np.ndarray], velocity: np.ndarray, height: float, timing: Timing
) -> tuple[np.ndarray, list[np.ndarray]]:
    """(times from the follow start, tip poses) of the follow path. grasp_at(tau): the tip's grasp pose over the
    object tau seconds after the start. The tool starts at rest `height` above grasp_at(ramp / 2) and accelerates
    uniformly to `velocity`, which puts it above grasp_at(tau) from tau = ramp on; it descends (half a cosine) to the
    grasp, stays there for `close`, rises back by `height`, then decelerates uniformly to rest."""
    ramp, end_lift = timing.ramp, timing.ramp + timing.descend + timing.close + timing.lift
    start = grasp_at(ramp / 2.0)
    count = int(math.ceil(timing.total / timing.step - 1e-9))
    times = np.linspace(0.0, timing.total, count + 1)
    poses = []
    for tau in times:
        if tau <= ramp:
            travel = tau * tau / (2.0 * ramp)
        elif tau <= end_lift:
            travel = tau - ramp / 2.0
        else:
            after = tau - end_lift
            travel = end_lift - ramp / 2.0 + after - after * after / (2.0 * ramp)
        down = tau - ramp
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


def timed_trajectory(solution: RobotTrajectory, times: np.ndarray) -> RobotTrajectory:
    """The path's points at the given times, velocities by central differences (zero at both ends)."""
    points = solution.joint_trajectory.points
    positions = np.array([p.positions for p in points])
    velocities = np.zeros_like(positions)
    velocities[1:-1] = (positions[2:] - positions[:-2]) / (times[2:] - times[:-2])[:, None]
    for point, t, v in zip(points, times, velocities, strict=True):
        point.time_from_start = rospy.Duration.from_sec(float(t))
        point.velocities = list(v)
        point.accelerations = []
    return solution


class _Failed(Exception):  # noqa: N818 (internal: ends a pick with its failure class)
    def __init__(self, failure: str, message: str) -> None:
        super().__init__(message)
        self.failure = failure


class _MovingPick:
    def __init__(self, driver: ArmDriver, target: MovingObject, timing: Timing) -> None:
        self.driver, self.target, self.timing = driver, target, timing
        self.arm = driver.arm
        # A conveyor moves objects horizontally: the vertical part of a velocity (a fresh object settling, bouncing)
        # would be extrapolated into the belt.
        self.velocity = np.array([target.velocity[0], target.velocity[1], 0.0])
        self.ik_service = PersistentService(resolve(driver.ns, "compute_ik"), GetPositionIK)
        geometry = object_geometry(target.pose, target.shape)
        self.height = geometry.height
        try:
            tcp, _ = grasp_tcp_pose(geometry, driver.grasp_spec)
        except SixdofCommanderError as err:
            raise _Failed(UNREACHABLE, f"no top-down grasp: {err}") from err
        self.grasp0 = tip_pose(tcp, driver.grasp_spec)  # the tip's grasp pose over the object at its stamp

    def grasp_at(self, t: float) -> np.ndarray:
        """The tip's grasp pose over the object at ROS time t."""
        pose = self.grasp0.copy()
        pose[:3, 3] += self.velocity * (t - self.target.stamp)
        return pose

    def nearest_start(self) -> float:
        """The follow start that puts the middle of the gripper's closing where the object passes nearest the planning
        frame's origin (the arm's base), in the horizontal plane; -inf for an object at rest."""
        p, v = self.target.pose[:2, 3], self.velocity[:2]
        if float(v @ v) < 1e-12:
            return -math.inf
        nearest = self.target.stamp - float(p @ v) / float(v @ v)
        return nearest - self.timing.grasp_time - self.timing.close / 2.0

    def plan_approach(self, lead: float) -> tuple[RobotTrajectory, float]:
        """(approach plan, follow start time). The start puts the grasp where the object passes nearest the arm's
        base, or `lead` s from now if that is sooner; later when the approach takes longer (three tries)."""
        nearest = self.nearest_start()
        start = max(rospy.get_time() + lead, nearest)
        for _ in range(3):
            pre = raised(self.grasp_at(start + self.timing.ramp / 2.0), self.driver.approach_distance)
            self.arm.set_start_state_to_current_state()
            self.arm.set_pose_target(pose_from_matrix(pre))
            ok, plan, _, error = self.arm.plan()
            if not ok:
                where = f"({pre[0, 3]:.3f}, {pre[1, 3]:.3f}, {pre[2, 3]:.3f})"
                if error.val not in (MoveItErrorCodes.NO_IK_SOLUTION, MoveItErrorCodes.GOAL_IN_COLLISION):
                    raise _Failed(FAILED, f"planning to the pre-grasp point {where} failed: {self.arm.last_error}")
                # Out of reach after the object passed the arm's base: it was missed.
                kind = MISSED if start > nearest + 1e-9 else UNREACHABLE
                raise _Failed(kind, f"no arm pose at the pre-grasp point {where}: {self.arm.last_error}")
            duration = plan.joint_trajectory.points[-1].time_from_start.to_sec()
            late = rospy.get_time() + duration + self.timing.margin - start
            if late <= 0.0:
                return plan, start
            start += late + 0.2
        raise _Failed(MISSED, "the arm cannot get ahead of the object (three approach plans were too slow)")

    def follow(self, plan: RobotTrajectory, start: float) -> RobotTrajectory:
        """The follow path from the approach's last state, timed to the object: one IK solution (move_group's
        compute_ik, seeded with the previous point's) per point."""
        times, poses = follow_path(
            lambda tau: self.grasp_at(start + tau), self.velocity, self.driver.approach_distance, self.timing
        )
        last = plan.joint_trajectory
        trajectory = RobotTrajectory()
        trajectory.joint_trajectory.joint_names = list(last.joint_names)
        positions = [np.asarray(last.points[-1].positions, dtype=float)]
        request = GetPositionIKRequest()
        request.ik_request.group_name = self.arm.get_name()
        request.ik_request.ik_link_name = self.arm.get_end_effector_link()
        request.ik_request.avoid_collisions = False  # the tool meets the object, and the belt under it
        request.ik_request.robot_state.is_diff = True
        request.ik_request.pose_stamped.header.frame_id = self.arm.get_planning_frame()
        for k, pose in enumerate(poses[1:], start=1):
            request.ik_request.robot_state.joint_state = JointState(name=last.joint_names, position=positions[-1])
            request.ik_request.pose_stamped.pose = pose_from_matrix(pose)
            try:
                response = call_service(self.ik_service, request, SERVICE_TIMEOUT)
            except (rospy.ServiceException, rospy.ROSException) as err:
                raise SixdofCommanderError(f"compute_ik failed: {err}") from err
            where = f"point {k}/{len(poses) - 1} ({pose[0, 3]:.3f}, {pose[1, 3]:.3f}, {pose[2, 3]:.3f})"
            if response.error_code.val != MoveItErrorCodes.SUCCESS:
                raise _Failed(UNREACHABLE, f"no IK solution for the follow path's {where}")
            solution = dict(
                zip(response.solution.joint_state.name, response.solution.joint_state.position, strict=True)
            )
            q = np.array([solution[name] for name in last.joint_names])
            jump = float(np.max(np.abs(q - positions[-1])))
            if jump > MAX_JUMP:
                raise _Failed(UNREACHABLE, f"the follow path's IK jumps {jump:.2f} rad at its {where}")
            positions.append(q)
        for q in positions:
            trajectory.joint_trajectory.points.append(JointTrajectoryPoint(positions=list(q)))
        return timed_trajectory(trajectory, times)

    def attached(self) -> bool:
        return bool(self.driver.get_object_state(self.target.name).attached_to)

    def run(self, lead: float) -> float:
        """Pick; the ROS time the gripper closed. _Failed says why not."""
        if not self.driver.gripper_open():
            raise _Failed(FAILED, self.driver.last_failure)
        plan, start = self.plan_approach(lead)
        trajectory = self.follow(plan, start)
        if not self.arm.execute(plan, wait=True):
            raise _Failed(FAILED, f"the approach failed: {self.arm.last_error}")
        wait = start - rospy.get_time()
        if wait < -self.timing.step:
            raise _Failed(MISSED, f"at the pre-grasp point {-wait:.2f} s after the object")
        rospy.sleep(max(wait, 0.0))
        executed: list[bool] = []
        runner = threading.Thread(target=lambda: executed.append(self.arm.execute(trajectory, wait=True)))
        runner.start()
        rospy.sleep(max(start + self.timing.grasp_time - rospy.get_time(), 0.0))
        grasp_time = rospy.get_time()
        closed = self.driver.gripper_close()
        # The grasp fix attaches a squeezed object within a few of its updates: until then, or the lift's end.
        lifted = start + self.timing.total - self.timing.ramp
        held = closed and self.attached()
        while closed and not held and rospy.get_time() < lifted and not rospy.is_shutdown():
            rospy.sleep(0.02)
            held = self.attached()
        runner.join()
        if not executed or not executed[0]:
            raise _Failed(FAILED, f"the follow path failed: {self.arm.last_error}")
        if not held:
            why = self.driver.last_failure if not closed else "the gripper closed but holds nothing"
            raise _Failed(NOT_GRASPED, why)
        if not self.attached():
            raise _Failed(DROPPED, "held after closing, lost during the lift")
        round_ = self.target.shape.type == SolidPrimitive.SPHERE
        if not self.driver.hold(self.target.name, self.height, round_):
            raise _Failed(FAILED, self.driver.last_failure)
        return grasp_time


def pick_moving(
    driver: ArmDriver, target: str | MovingObject | DetectedObject, timing: Timing | None = None, lead: float = 1.5
) -> MovingPickResult:
    """Grasp a moving object on the fly and lift it (module docstring). target: a simulator object's name (its
    pose and velocity from the simulator), a MovingObject, or a DetectedObject with a tracked velocity. The follow path
    starts so that the gripper closes where the object passes nearest the arm's base, or at the earliest `lead` s
    from now (later when the approach needs longer). On success the driver holds the
    object (ArmDriver.place puts it down)."""
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
    result = MovingPickResult(target.name)
    try:
        result.grasp_time = _MovingPick(driver, target, timing or Timing()).run(float(lead))
    except _Failed as failed:
        result.failure, result.message = failed.failure, f"pick_moving '{target.name}': {failed}"
        rospy.logerr(result.message)
    return result
