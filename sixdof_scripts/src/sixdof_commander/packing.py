"""Packing what a conveyor brings into a box: which object to pick next, picking it on the fly (moving_pick) and
putting it upright into its slot (pack_pattern), and checking where it ended up. pack_objects.py and the packing
benchmark (bench/pack_bench.py) are loops over these. Arriving objects are the simulator's (its object states): the
dynamic objects resting on the conveyor's belt.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
import rospy
from moveit_msgs.msg import RobotState, RobotTrajectory
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import ConveyorStates, ObjectStates
from sixdof_msgs.srv import DeleteObject

from ._ros import resolve
from .arm_driver import ArmDriver, pose_from_matrix
from .grasping import object_geometry, raised
from .moving_pick import MISSED, UNREACHABLE, MovingPickResult, Timing, pick_moving
from .pack_pattern import Slot
from .sim_world import Bin, Conveyor
from .transforms import matrix_from_pose, matrix_from_quaternion

PLACE_FAILED = "place failed"
# s an object must have ridden at the belt's speed before it is picked: one that has just landed on the belt may still
# slide or turn, and its predicted path miss the tool (a suction cup then comes down beside its top).
SETTLE = 0.3
# s ahead the packer asks pick_moving to meet an object at the earliest: about the shortest approach from the box;
# pick_moving meets it later when the approach takes longer.
PACK_LEAD = 0.6
# s the cup stays on the place while its vacuum goes off (the command is sent a third of the way into it).
RELEASE_DWELL = 0.15
# An object leaning by more than this from upright is not upright in its slot.
UPRIGHT_TOLERANCE = math.radians(10.0)
__all__ = ["PLACE_FAILED", "Packer", "SlotCheck"]


@dataclass(frozen=True)
class SlotCheck:
    """Where a packed object rests against its slot: horizontal error (m), lean (rad), and whether both are within
    the tolerance and UPRIGHT_TOLERANCE."""

    error: float
    lean: float
    ok: bool


class Packer:
    """Picks objects off `conveyor` and puts them into the slots of `box` with `driver`."""

    def __init__(
        self, driver: ArmDriver, conveyor: Conveyor, box: Bin, timing: Timing | None = None, pick_before: float = 0.0
    ) -> None:
        """timing: pick_moving's (None: its default for the driver's tool). pick_before: m along the belt from its
        centre (downstream positive); an object past it is left to ride on (`passed`)."""
        self.driver, self.conveyor, self.box = driver, conveyor, box
        self.timing = timing
        self.pick_before = pick_before
        self.direction = np.asarray(conveyor.direction)
        self.states: ObjectStates | None = None
        # The belt is watched on every object state, also while the arm is busy: every object that was on it ends
        # claimed (picked or being picked) or passed.
        self._lock = threading.Lock()
        self.claimed: set[str] = set()
        self.passed: dict[str, tuple[float, str]] = {}  # name: (ROS time, how it passed)
        self.seen: set[str] = set()
        self.riding_since: dict[str, float] = {}  # name: ROS time it has ridden at the belt's speed since
        self.last_failure = ""  # what put_down found failed
        self.delete = rospy.ServiceProxy(resolve(driver.ns, "sixdof_sim/delete_object"), DeleteObject)
        self.belt_speed = math.nan  # m/s, the simulator's current speed of the conveyor (nan until it says)
        self.speeds: list[tuple[float, float]] = []  # (ROS time, belt speed m/s), every 0.5 s
        rospy.Subscriber(resolve(driver.ns, "sixdof_sim/object_states"), ObjectStates, self._on_states, queue_size=1)
        rospy.Subscriber(
            resolve(driver.ns, "sixdof_sim/conveyor_states"), ConveyorStates, self._on_conveyors, queue_size=1
        )

    def _on_states(self, msg: ObjectStates) -> None:
        now = rospy.get_time()
        with self._lock:
            self.states = msg
            on = self._on_belt(msg, riding=False)
            self.seen |= on.keys()
            riding = self._on_belt(msg, riding=True)
            self.riding_since = {name: self.riding_since.get(name, now) for name in riding}
            for name, along in on.items():
                if along >= self.pick_before:
                    self.passed[name] = (now, f"rode past {self.pick_before:g} m along the belt unpicked")
            present = set(msg.name)
            for name in self.seen - on.keys() - self.claimed - self.passed.keys():
                how = "left the belt unpicked" if name in present else "rode off the belt's end unpicked (deleted)"
                self.passed[name] = (now, how)

    def _on_conveyors(self, msg: ConveyorStates) -> None:
        if self.conveyor.name in msg.conveyor:
            self.belt_speed = msg.speed[msg.conveyor.index(self.conveyor.name)]
            now = rospy.get_time()
            if not self.speeds or now >= self.speeds[-1][0] + 0.5:
                self.speeds.append((now, self.belt_speed))

    def on_belt(self, position: np.ndarray) -> float | None:
        """How far along the belt (m from its centre, downstream positive) an object resting on it is; None off it."""
        centre = np.asarray(self.conveyor.position)
        rotation = matrix_from_quaternion(self.conveyor.orientation)
        local = rotation.T @ (position - centre)
        half = np.asarray(self.conveyor.size) / 2.0
        if abs(local[0]) > half[0] or abs(local[1]) > half[1] or not half[2] < local[2] < half[2] + 0.1:
            return None
        return float(local[0]) if self.direction @ rotation[:, 0] > 0.0 else -float(local[0])

    def _on_belt(self, states: ObjectStates, riding: bool) -> dict[str, float]:
        """The objects of `states` on the belt, neither claimed nor passed, and how far along it each is; riding:
        only those moving with the belt (within 5 % of its speed: a fresh object still landing on it would be
        mispredicted)."""
        found = {}
        for name, pose, twist, holder in zip(states.name, states.pose, states.twist, states.attached_to, strict=True):
            if holder or name in self.claimed or name in self.passed or name == self.conveyor.name:
                continue
            along = self.on_belt(np.array([pose.position.x, pose.position.y, pose.position.z]))
            if along is None:
                continue
            speed = float(self.direction @ [twist.linear.x, twist.linear.y, twist.linear.z])
            if not riding or abs(speed - self.belt_speed) <= 0.05 * abs(self.belt_speed):
                found[name] = along
        return found

    def take_next(self) -> str | None:
        """Claim the object furthest downstream on the belt that has ridden with it for SETTLE s (upstream of
        pick_before)."""
        with self._lock:
            waiting = self._on_belt(self.states, riding=True) if self.states is not None else {}
            now = rospy.get_time()
            settled = now - SETTLE
            waiting = {name: along for name, along in waiting.items() if self.riding_since.get(name, now) <= settled}
            if not waiting:
                return None
            name = max(waiting, key=waiting.get)
            self.claimed.add(name)
            return name

    def pack(self, name: str, slot: Slot) -> MovingPickResult:
        """Pick the object (claimed by take_next) off the belt and put it upright into the slot (PLACE_FAILED when
        that fails). After a failure the gripper is open and nothing is held (an object the gripper cannot let go of
        is deleted from the simulator); the arm is back at its home state unless the pick was MISSED or UNREACHABLE
        (found before the arm moved)."""
        state = self.driver.get_object_state(name).object
        height = object_geometry(matrix_from_pose(state.pose), state.shape).height
        result = pick_moving(self.driver, name, self.timing, PACK_LEAD)
        if result.ok and not self.put_down(name, [slot.x, slot.y, self.box.centre[2] + slot.bottom + height / 2.0]):
            result.failure, result.message = PLACE_FAILED, f"{name}: {self.last_failure}"
        if not result.ok and result.failure not in (MISSED, UNREACHABLE):  # those two fail before the arm moves
            self.recover(name)
        return result

    def recover(self, name: str) -> None:
        driver = self.driver
        if not driver.gripper_open() and driver.get_object_state(name).attached_to:
            rospy.logwarn(f"'{name}' stays in the gripper: deleting it")
            self.delete(name)
            driver.gripper_open()
        if name in driver.scene.get_attached_object_names():
            driver.scene.detach_object(name)
        driver.forget_held()
        driver.moveto_named(driver.home)

    def put_down(self, name: str, position: list[float]) -> bool:
        """Place the held object at position and retreat: a suction cup in one motion (release_in_one_motion).
        Opening fingers may stop at a neighbour or the box's wall, or on the object while the grasp fix still holds it
        (it lets go within a few of its updates): the object is put down when the grasp fix has let it go."""
        driver = self.driver
        if driver.suction:
            self.last_failure = release_in_one_motion(driver, name, position)
            return not self.last_failure
        self.last_failure = ""
        if not driver.release_at(position):
            self.last_failure = driver.last_failure
            if not driver.last_failure.startswith("gripper did not open"):
                return False
            rospy.sleep(0.5)
            if driver.get_object_state(name).attached_to:
                return False
            if name in driver.scene.get_attached_object_names() and not driver.scene.detach_object(name):
                rospy.logwarn("detaching '%s' in the planning scene failed", name)
            driver.forget_held()
        if driver.retreat():
            return True
        self.last_failure = driver.last_failure
        return False

    def check(self, name: str, slot: Slot, tolerance: float) -> SlotCheck:
        """Where the object rests against its slot (the simulator's pose of it)."""
        pose = matrix_from_pose(self.driver.get_object_state(name).object.pose)
        error = math.dist(pose[:2, 3], (slot.x, slot.y))
        lean = math.acos(min(1.0, abs(float(pose[2, 2]))))
        return SlotCheck(error, lean, error <= tolerance and lean <= UPRIGHT_TOLERANCE)


def _end_state(trajectory: RobotTrajectory) -> RobotState:
    """The state where `trajectory` ends."""
    points = trajectory.joint_trajectory
    return RobotState(joint_state=JointState(name=list(points.joint_names), position=list(points.points[-1].positions)))


def _append(trajectory: RobotTrajectory, part: RobotTrajectory, pause: float) -> None:
    """Append `part` (starting at rest where `trajectory` ends at rest) `pause` s after trajectory's end."""
    points = trajectory.joint_trajectory.points
    offset = points[-1].time_from_start + rospy.Duration.from_sec(pause) if points else rospy.Duration(0)
    for point in part.joint_trajectory.points[1:] if points else part.joint_trajectory.points:
        points.append(
            JointTrajectoryPoint(
                positions=point.positions,
                velocities=point.velocities,
                accelerations=point.accelerations,
                time_from_start=point.time_from_start + offset,
            )
        )


def release_in_one_motion(driver: ArmDriver, name: str, position: list[float]) -> str:
    """Put the object a suction cup holds down at `position` (its centre) and retreat, as one trajectory: a plan to
    `approach_distance` above the place, straight down, RELEASE_DWELL s on the place while the vacuum goes off, and
    straight up. The vacuum goes off when the trajectory is at the place (timed from when it was sent); the object is
    put down once the simulator has let it go. '' on success, else what failed."""
    arm = driver.arm
    place = driver.place_tip(position)
    above = raised(place, driver.approach_distance)
    arm.set_start_state_to_current_state()
    arm.set_pose_target(pose_from_matrix(above))
    ok, trajectory, _, _ = arm.plan()
    if not ok:
        return f"place: planning above the slot failed: {arm.last_error}"
    try:
        for what, target, pause in (("down onto", place, 0.0), ("up from", above, RELEASE_DWELL)):
            arm.set_start_state(_end_state(trajectory))
            path, fraction = arm.compute_cartesian_path([pose_from_matrix(target)], driver.cartesian_step, 0.0, False)
            if fraction < 1.0 - 1e-6:
                return f"place: straight {what} the slot only {max(fraction, 0.0) * 100:.0f}% feasible"
            if not pause:
                at_place = path.joint_trajectory.points[-1].time_from_start.to_sec()
                at_place += trajectory.joint_trajectory.points[-1].time_from_start.to_sec()
            _append(trajectory, path, pause)
    finally:
        arm.set_start_state_to_current_state()
    sent = rospy.get_time()
    executed: list[bool] = []
    runner = threading.Thread(target=lambda: executed.append(arm.execute(trajectory, wait=True)))
    runner.start()
    rospy.sleep(max(sent + at_place + RELEASE_DWELL / 3.0 - rospy.get_time(), 0.0))
    why = "" if driver.gripper_open() else driver.last_failure
    held = not why
    while held and rospy.get_time() < sent + at_place + RELEASE_DWELL and not rospy.is_shutdown():
        held = bool(driver.get_object_state(name).attached_to)
        if held:
            rospy.sleep(0.02)
    if not why and name in driver.scene.get_attached_object_names() and not driver.scene.detach_object(name):
        rospy.logwarn("detaching '%s' in the planning scene failed", name)
    runner.join()
    if why:
        return why
    if held:
        return f"place: the cup still holds '{name}' with the vacuum off"
    driver.forget_held()
    return "" if executed and executed[0] else f"place: the motion failed: {arm.last_error}"
