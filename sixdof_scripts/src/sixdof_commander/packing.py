"""Packing what a conveyor brings into a box: which object to pick next, picking it on the fly (moving_pick) and
putting it upright into its slot (pack_pattern), and checking where it ended up. pack_objects.py and the packing
benchmark (bench/pack_bench.py) are loops over these. Arriving objects are the simulator's (its object states): the
dynamic objects resting on the conveyor's belt.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import rospy
from moveit_msgs.msg import RobotTrajectory

from sixdof_msgs.msg import ConveyorStates, ObjectStates
from sixdof_msgs.srv import DeleteObject

from ._ros import resolve
from .arm_driver import ArmDriver
from .blending import blended, end_state
from .exceptions import SixdofCommanderError
from .grasping import object_geometry, raised
from .moving_pick import (
    MISSED,
    UNREACHABLE,
    MovingPickResult,
    PlannedPick,
    Timing,
    plan_pick_moving,
    run_pick_moving,
)
from .pack_pattern import Slot
from .sim_world import Bin, Conveyor
from .transforms import matrix_from_pose, matrix_from_quaternion, pose_from_matrix

PLACE_FAILED = "place failed"
# s an object must have ridden at the belt's speed before it is picked: one that has just landed on the belt may still
# slide or turn, and its predicted path miss the tool (a suction cup then comes down beside its top).
SETTLE = 0.3
# s ahead the packer asks pick_moving to meet an object at the earliest: about the shortest approach from the box;
# pick_moving meets it later when the approach takes longer.
PACK_LEAD = 0.6
# s after the arm is due at the place that the vacuum goes off (the trajectory starts a little after it is sent), and
# the most s after that time the cup waits for the simulator to let the object go (it retreats as soon as it has).
RELEASE_DELAY = 0.02
RELEASE_WAIT = 0.15
# s after the vacuum goes off that the next pick, planned while the cup moves to the slot, is due to be sent (the
# release is confirmed and the place's bookkeeping done by then).
NEXT_PICK_AFTER = 0.02
# s before the next pick is due to be sent that plan_next stops waiting for an object to plan it for (planning one
# takes up to about 0.13 s): an object that has settled on the belt by then is planned while the place runs.
PLAN_AHEAD = 0.15
# s the cup may wait on the place for the next object to pick, whose approach continues the retreat without a stop
# (a retreat on its own, then the approach, take longer than the two blended and this wait): after that it retreats.
RETREAT_AFTER = 0.5
# An object leaning by more than this from upright is not upright in its slot.
UPRIGHT_TOLERANCE = math.radians(10.0)
__all__ = ["PLACE_FAILED", "RETREAT_AFTER", "Packer", "SlotCheck"]


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
        self.durations = (math.nan, math.nan)  # s (ROS time) the last pack's pick and place took
        # A suction place's retreat up from the slot, not yet run: the next pick's approach continues it.
        self.retreat: RobotTrajectory | None = None
        self.placed_at = math.nan  # ROS time the last suction place ended
        # The next pick, planned while the last suction place ran (its approach continues `retreat`).
        self.next_pick: PlannedPick | None = None
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
        """The object of the pick planned during the last place, if any; else claim the object furthest downstream
        on the belt that has ridden with it for SETTLE s (upstream of pick_before)."""
        if self.next_pick is not None:
            return self.next_pick.result.object
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
        (found before the arm moved). After a suction place the cup stays on the slot, its retreat pending (the next
        pack's approach continues it, idle() runs it alone)."""
        state = self.driver.get_object_state(name).object
        height = object_geometry(matrix_from_pose(state.pose), state.shape).height
        began = rospy.get_time()
        planned, self.next_pick = self.next_pick, None
        if planned is None or planned.result.object != name or not planned.fits():
            planned = plan_pick_moving(self.driver, name, self.timing, PACK_LEAD, self.retreat)
        result = run_pick_moving(planned)
        picked = rospy.get_time()
        if result.moved:
            self.retreat = None
        if result.ok and not self.put_down(name, [slot.x, slot.y, self.box.centre[2] + slot.bottom + height / 2.0]):
            result.failure, result.message = PLACE_FAILED, f"{name}: {self.last_failure}"
        self.durations = (picked - began, rospy.get_time() - picked)
        if not result.ok and result.failure not in (MISSED, UNREACHABLE):  # those two fail before the arm moves
            self.recover(name)
        return result

    def idle(self, after: float = 0.0) -> None:
        """Run the retreat from the last place if it is still to run (no next pick continued it) and the place ended
        `after` s ago or earlier."""
        if self.retreat is not None and rospy.get_time() >= self.placed_at + after:
            retreat, self.retreat = self.retreat, None
            if not self.driver.arm.execute(retreat, wait=True):
                rospy.logwarn(f"the retreat from the box failed: {self.driver.arm.last_error}")

    def recover(self, name: str) -> None:
        driver = self.driver
        self.idle()
        if not driver.gripper_open() and driver.get_object_state(name).attached_to:
            rospy.logwarn(f"'{name}' stays in the gripper: deleting it")
            self.delete(name)
            driver.gripper_open()
        if name in driver.scene.get_attached_object_names():
            driver.scene.detach_object(name)
        driver.forget_held()
        driver.moveto_named(driver.home)

    def put_down(self, name: str, position: list[float]) -> bool:
        """Place the held object at position and retreat: a suction cup without stopping above the slot
        (release_in_one_motion), its retreat left to the next pick's approach (`retreat`; idle() runs it alone).
        Opening fingers may stop at a neighbour or the box's wall: the object is put down when the grasp fix has let it
        go."""
        driver = self.driver
        if driver.suction:
            self.last_failure, self.retreat = release_in_one_motion(driver, name, position, self.plan_next)
            self.placed_at = rospy.get_time()
            if self.last_failure and self.next_pick is not None:
                with self._lock:  # its approach would continue a retreat that does not follow: picked afresh
                    self.claimed.discard(self.next_pick.result.object)
                self.next_pick = None
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

    def plan_next(self, retreat: RobotTrajectory, ready: float) -> None:
        """Plan the next pick (take_next's object: one waiting, or the first to settle on the belt until
        PLAN_AHEAD s before `ready`), its approach continuing `retreat` from ROS time `ready` on (next_pick). A plan
        that MISSED gives its object back to take_next; one that failed otherwise stays next_pick, and pack() plans
        it afresh from where the place ends."""
        name = self.take_next()
        while name is None and rospy.get_time() < ready - PLAN_AHEAD and not rospy.is_shutdown():
            rospy.sleep(0.02)
            name = self.take_next()
        if name is None:
            return
        try:
            planned = plan_pick_moving(self.driver, name, self.timing, PACK_LEAD, retreat, ready)
        except SixdofCommanderError as err:
            rospy.logwarn(f"planning the pick of '{name}' ahead: {err}")
            planned = None
        if planned is None or planned.result.failure == MISSED:
            with self._lock:
                self.claimed.discard(name)
            return
        self.next_pick = planned  # one that failed otherwise is planned afresh from where the place ends

    def check(self, name: str, slot: Slot, tolerance: float) -> SlotCheck:
        """Where the object rests against its slot (the simulator's pose of it)."""
        pose = matrix_from_pose(self.driver.get_object_state(name).object.pose)
        error = math.dist(pose[:2, 3], (slot.x, slot.y))
        lean = math.acos(min(1.0, abs(float(pose[2, 2]))))
        return SlotCheck(error, lean, error <= tolerance and lean <= UPRIGHT_TOLERANCE)


def release_in_one_motion(
    driver: ArmDriver,
    name: str,
    position: list[float],
    meanwhile: Callable[[RobotTrajectory, float], None] | None = None,
) -> tuple[str, RobotTrajectory | None]:
    """Put the object a suction cup holds down at `position` (its centre) without stopping above it: a plan to
    `approach_distance` above the place and the straight descent onto it as one blended motion (blending.blended),
    then the vacuum off when the arm is at the place (RELEASE_DELAY after it is due there, timed from when the motion
    was sent); the object is put down once the simulator has let it go (within RELEASE_WAIT). ('' and the
    straight retreat up from the place, not yet run; or what failed and None). meanwhile(retreat, ready), if given,
    runs in a thread of its own while the arm moves to the place (e.g. planning the next motion, to be sent at ROS time
    `ready`, NEXT_PICK_AFTER s after the vacuum goes off); it has ended when this returns."""
    arm = driver.arm
    place = driver.place_tip(position)
    above = raised(place, driver.approach_distance)
    try:
        arm.set_start_state_to_current_state()
        arm.set_pose_target(pose_from_matrix(above))
        ok, transit, _, _ = arm.plan()
        if not ok:
            return f"place: planning above the slot failed: {arm.last_error}", None
        paths = []
        for what, start, target in (("down onto", transit, place), ("up from", None, above)):
            arm.set_start_state(end_state(start if start is not None else paths[-1]))
            path, fraction = arm.compute_cartesian_path([pose_from_matrix(target)], driver.cartesian_step, 0.0, False)
            if fraction < 1.0 - 1e-6:
                return f"place: straight {what} the slot only {max(fraction, 0.0) * 100:.0f}% feasible", None
            paths.append(path)
    finally:
        arm.set_start_state_to_current_state()
    try:
        trajectory = blended(driver, [transit, paths[0]])
    except SixdofCommanderError as err:
        return f"place: {err}", None
    at_place = trajectory.joint_trajectory.points[-1].time_from_start.to_sec()
    sent = rospy.get_time()
    executed: list[bool] = []
    runner = threading.Thread(target=lambda: executed.append(arm.execute(trajectory, wait=True)))
    runner.start()
    ahead = None
    if meanwhile is not None:
        ready = sent + at_place + RELEASE_DELAY + NEXT_PICK_AFTER
        ahead = threading.Thread(target=meanwhile, args=(paths[1], ready))
        ahead.start()
    rospy.sleep(max(sent + at_place + RELEASE_DELAY - rospy.get_time(), 0.0))
    why = "" if driver.gripper_open() else driver.last_failure
    held = not why
    while held and rospy.get_time() < sent + at_place + RELEASE_WAIT and not rospy.is_shutdown():
        held = bool(driver.get_object_state(name).attached_to)
        if held:
            rospy.sleep(0.01)
    if not why and name in driver.scene.get_attached_object_names() and not driver.scene.detach_object(name):
        rospy.logwarn("detaching '%s' in the planning scene failed", name)
    runner.join()
    if ahead is not None:
        ahead.join()
    if why:
        return why, None
    if held:
        return f"place: the cup still holds '{name}' with the vacuum off", None
    driver.forget_held()
    if not (executed and executed[0]):
        return f"place: the motion failed: {arm.last_error}", None
    return "", paths[1]
