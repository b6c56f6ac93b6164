#!/usr/bin/env python3
"""Sort what the camera sees: pick every detected object (sixdof_perception's detected_objects) and place it in
the bin of its colour (the bins of the simulator's world, its ~world parameter), re-detecting after each
placement and printing each object's outcome. Objects are chosen and located from the camera only; the
simulator's ground truth is read once at the end, to check that every object rests in the bin of its colour.

    rosrun sixdof_scripts sort_objects.py      (with the stack on a world with bins, e.g. sorting.yaml)

Exit codes: 0 every object sorted (or nothing to sort), 1 an object could not be sorted (unreachable,
dropped, no bin of its colour, ...) or the final check failed, 2 bad arguments, a missing node or a world
without bins.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import asdict, dataclass

import numpy as np
import rospy
from sixdof_commander import ArmDriver, SixdofCommanderError
from sixdof_commander.colors import color_class
from sixdof_commander.grasping import grasp_tcp_pose, object_geometry, place_tcp_pose, raised, tip_pose
from sixdof_commander.sim_world import WORLD_PARAMETER, Bin, SimWorldError, wait_for_world
from sixdof_commander.transforms import matrix_from_pose, pose_from_matrix

from sixdof_msgs.msg import DetectedObject, DetectedObjectArray, ObjectStates

# Places in a bin (fractions of its inner half size): towards the corners, far enough from each other for 6 cm
# objects and from the walls for the closed fingers, and the centre. The freest one is used.
SLOTS = ((-0.35, -0.35), (0.35, 0.35), (-0.35, 0.35), (0.35, -0.35), (0.0, 0.0))


@dataclass
class Outcome:
    id: str
    label: str
    position: tuple[float, float, float]
    bin: str
    result: str  # ok, or the failure class: no_bin, unreachable, grasp_missed, place_failed, ...
    detail: str = ""
    seconds: float = 0.0


class Sorter:
    def __init__(self, driver: ArmDriver, world_bins: list[Bin], home: str, ns: str, settle: float) -> None:
        self.driver = driver
        self.bins = world_bins
        self.home = home
        self.settle = settle
        self.topic = f"{ns.rstrip('/')}/detected_objects" if ns else "detected_objects"
        self.placed: dict[str, list[tuple[float, float]]] = {}
        self.latest: DetectedObjectArray | None = None
        rospy.Subscriber(self.topic, DetectedObjectArray, self._on_detected, queue_size=1)

    def _on_detected(self, msg: DetectedObjectArray) -> None:
        self.latest = msg

    def detect(self, timeout: float = 30.0) -> list[DetectedObject]:
        """Objects of a camera frame taken after the robot stopped (plus settle seconds of simulated time)."""
        after = rospy.Time.now() + rospy.Duration(self.settle)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline and not rospy.is_shutdown():
            msg = self.latest
            if msg is not None and msg.header.stamp >= after:
                return list(msg.objects)
            time.sleep(0.02)
        topic = rospy.resolve_name(self.topic)
        raise SixdofCommanderError(f"no {topic} frame within {timeout:g} s: is the perception node running?")

    def bin_of(self, obj: DetectedObject) -> Bin | None:
        return next((b for b in self.bins if b.color == obj.color), None)

    def in_a_bin(self, obj: DetectedObject) -> bool:
        p = obj.pose.pose.position
        return any(b.contains(p.x, p.y) for b in self.bins)

    def slot(self, target: Bin, occupied: list[tuple[float, float]]) -> tuple[float, float, float]:
        """The place in the bin farthest from the objects seen in it (and from the ones put there since)."""
        hx, hy = target.inner_half()
        inside = [p for p in occupied + self.placed.get(target.name, []) if target.contains(*p)]
        candidates = [target.to_world(fu * hx, fv * hy) for fu, fv in SLOTS]
        best = max(candidates, key=lambda c: min((math.dist(c, p) for p in inside), default=math.inf))
        self.placed.setdefault(target.name, []).append(best)
        return best[0], best[1], target.centre[2]

    def _fail(self, outcome: Outcome, result: str) -> Outcome:
        outcome.result = result
        outcome.detail = self.driver.last_failure
        return outcome

    def sort_one(self, obj: DetectedObject, target: Bin, occupied: list[tuple[float, float]]) -> Outcome:
        p = obj.pose.pose.position
        outcome = Outcome(obj.id, obj.label, (p.x, p.y, p.z), target.name, "ok")
        driver, spec = self.driver, self.driver.grasp_spec
        pose = matrix_from_pose(obj.pose.pose)
        try:
            geometry = object_geometry(pose, obj.shape)
            tcp, width = grasp_tcp_pose(geometry, spec)
        except SixdofCommanderError as err:
            outcome.result, outcome.detail = "ungraspable", str(err)
            return outcome
        grasp_tip = tip_pose(tcp, spec)
        if not driver.gripper_open():
            return self._fail(outcome, "gripper_failed")
        if not driver.moveto_pose(pose_from_matrix(raised(grasp_tip, driver.approach_distance))):
            return self._fail(outcome, "unreachable")
        # Into contact: the fingers straddle the object (MoveIt's pick allows that too).
        if not driver.move_straight(grasp_tip, "approach", avoid_collisions=False):
            self._back_off()
            return self._fail(outcome, "unreachable")
        if not driver.gripper_close():
            self._back_off()
            return self._fail(outcome, "grasp_missed")
        # The simulator's grasp fix attaches a squeezed object within a few of its 4 Hz updates.
        rospy.sleep(0.75)
        if obj.id in driver.scene.get_known_object_names() and not driver.arm.attach_object(obj.id):
            rospy.logwarn("attaching '%s' in the planning scene failed", obj.id)
        tcp_now = matrix_from_pose(driver.arm.get_current_pose().pose) @ spec.tcp_in_tip
        object_in_tcp = np.linalg.inv(tcp_now) @ pose[:, 3]
        lift = raised(matrix_from_pose(driver.arm.get_current_pose().pose), driver.approach_distance)
        if not driver.move_straight(lift, "lift", avoid_collisions=False):
            return self._drop(obj.id, self._fail(outcome, "lift_failed"))
        x, y, z = self.slot(target, occupied)
        height = geometry.height
        place_tip = tip_pose(place_tcp_pose(np.array([x, y, z + height / 2.0]), object_in_tcp, spec.clearance), spec)
        if not driver.moveto_pose(pose_from_matrix(raised(place_tip, driver.approach_distance))):
            return self._drop(obj.id, self._fail(outcome, "place_unreachable"))
        if not driver.move_straight(place_tip, "place descent", avoid_collisions=False):
            return self._drop(obj.id, self._fail(outcome, "place_blocked"))
        # In a bin the opening fingers may stop at a wall: released is when they are clear of the object.
        opened = driver.gripper.open()
        if not opened.reached_goal:
            # Fingers held back while the grasp fix still held the object: once it lets go they open further.
            rospy.sleep(0.5)
            opened = driver.gripper.open()
        opening = driver.gripper_opening(opened.position)
        if opening < width + 0.002:
            outcome.detail = f"the gripper opened to {opening:.3f} m only, the object is {width:.3f} m"
            self._drop(obj.id, outcome)
            outcome.result = "release_failed"
            return outcome
        rospy.sleep(0.5)
        self._detach(obj.id)
        if not driver.retreat():
            return self._fail(outcome, "retreat_failed")
        return outcome

    def _detach(self, object_id: str) -> None:
        if object_id in self.driver.scene.get_attached_object_names() and not self.driver.arm.detach_object(object_id):
            rospy.logwarn("detaching '%s' in the planning scene failed", object_id)

    def _drop(self, object_id: str, outcome: Outcome) -> Outcome:
        """After a failure with the object in the hand: let it go where the hand is (it is detected again
        wherever it lands) and move up, so that the next attempt starts with an empty, clear hand."""
        self.driver.gripper_open()
        rospy.sleep(0.5)
        self._detach(object_id)
        self.driver.retreat()
        return outcome

    def _back_off(self) -> None:
        """After a failed approach or grasp: open and go up, so that the next attempt starts clear."""
        self.driver.gripper_open()
        self.driver.retreat()


def same_place(a: tuple[float, float, float], b: tuple[float, float, float], tolerance: float = 0.03) -> bool:
    return math.dist(a[:2], b[:2]) <= tolerance


def ground_truth(driver: ArmDriver, world_bins: list[Bin], ns: str) -> list[dict]:
    """Every dynamic simulator object: its colour class, where it rests and whether that is its bin."""
    topic = f"{ns.rstrip('/')}/sixdof_sim/object_states" if ns else "sixdof_sim/object_states"
    states = rospy.wait_for_message(topic, ObjectStates, timeout=10.0)
    results = []
    for name, pose in zip(states.name, states.pose, strict=True):
        described = driver.get_object_state(name).object
        if described.is_static:
            continue
        c = described.color
        color = color_class(c.r, c.g, c.b)
        home = next((b for b in world_bins if b.color == color), None)
        p = pose.position
        inside = home is not None and home.contains(p.x, p.y) and p.z < home.centre[2] + home.wall_height + 0.05
        results.append(
            {
                "name": name,
                "color": color,
                "bin": home.name if home else "",
                "position": [p.x, p.y, p.z],
                "in_bin": bool(inside),
            }
        )
    return results


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(
        "--home", help="named state of the arm to detect from (default: the arm group's first SRDF state)"
    )
    parser.add_argument("--max-attempts", type=int, default=2, help="attempts per object before it is skipped")
    parser.add_argument("--settle", type=float, default=0.5, help="simulated seconds before a frame counts")
    parser.add_argument("--velocity-scaling", type=float, default=0.5, help="max velocity scaling in (0, 1]")
    parser.add_argument("--json", default="", help="also write the outcomes and the final check to this file")
    parser.add_argument("--ns", default="", help="namespace of the planner, simulator and perception nodes")
    parser.add_argument("--world-wait", type=float, default=60.0, help="s to wait for the simulator's world")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    if args.max_attempts < 1:
        parser.error(f"--max-attempts must be >= 1, got {args.max_attempts}")
    if not math.isfinite(args.world_wait) or args.world_wait <= 0.0:
        parser.error(f"--world-wait must be > 0, got {args.world_wait}")
    if not math.isfinite(args.settle) or args.settle < 0.0:
        parser.error(f"--settle must be >= 0, got {args.settle}")
    rospy.init_node("sort_objects", anonymous=True)
    try:
        world = wait_for_world(rospy.names.ns_join(args.ns, WORLD_PARAMETER), args.world_wait)
    except SimWorldError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    if not world.bins:
        print(f"error: the simulator's world '{world.name}' has no bins", file=sys.stderr)
        return 2
    world_bins = list(world.bins)
    start = time.monotonic()
    outcomes: list[Outcome] = []
    try:
        driver = ArmDriver(
            ns=args.ns, velocity_scaling=args.velocity_scaling, acceleration_scaling=args.velocity_scaling
        )
        home = args.home or driver.home
        sorter = Sorter(driver, world_bins, home, args.ns, args.settle)
        attempts: list[tuple[tuple[float, float, float], int]] = []  # where an attempt failed, and how often
        if not driver.moveto_named(home):
            print(f"error: cannot reach '{home}': {driver.last_failure}", file=sys.stderr)
            return 1
        first = True
        while not rospy.is_shutdown():
            seen = sorter.detect()
            todo = [o for o in seen if not sorter.in_a_bin(o)]
            if first and not todo:
                print("nothing to sort")
                break
            if first:
                # A bound on the whole run: objects that keep falling somewhere new are not retried forever.
                budget = args.max_attempts * len(todo) + 2
            first = False
            if len(outcomes) >= budget:
                print(f"giving up after {len(outcomes)} attempts", file=sys.stderr)
                break
            chosen = None
            for obj in sorted(todo, key=lambda o: math.hypot(o.pose.pose.position.x, o.pose.pose.position.y)):
                p = obj.pose.pose.position
                failed = sum(n for where, n in attempts if same_place(where, (p.x, p.y, p.z)))
                if failed < args.max_attempts:
                    chosen = obj
                    break
            if chosen is None:
                break
            p = chosen.pose.pose.position
            where = (p.x, p.y, p.z)
            target = sorter.bin_of(chosen)
            if target is None:
                outcome = Outcome(chosen.id, chosen.label, where, "", "no_bin", f"no bin of colour '{chosen.color}'")
                attempts.append((where, args.max_attempts))
            else:
                t0 = time.monotonic()
                occupied = [(o.pose.pose.position.x, o.pose.pose.position.y) for o in seen if o.id != chosen.id]
                outcome = sorter.sort_one(chosen, target, occupied)
                outcome.seconds = time.monotonic() - t0
                if outcome.result != "ok":
                    attempts.append((where, 1))
            outcomes.append(outcome)
            verdict = "ok" if outcome.result == "ok" else f"FAILED ({outcome.result}: {outcome.detail})"
            print(
                f"{outcome.id:<18s} {outcome.label:<16s} at ({where[0]:.3f}, {where[1]:.3f}) -> "
                f"{outcome.bin or '-':<10s} {verdict}  ({outcome.seconds:.1f} s)",
                flush=True,
            )
            if not driver.moveto_named(home):
                print(f"error: cannot return to '{home}': {driver.last_failure}", file=sys.stderr)
                break
        # Skipped objects: detected, still out of the bins after all attempts.
        truth = ground_truth(driver, world_bins, args.ns)
    except SixdofCommanderError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    misplaced = [t for t in truth if not t["in_bin"]]
    for t in truth:
        x, y, z = t["position"]
        state = "in its bin" if t["in_bin"] else "NOT in its bin"
        print(f"check: {t['name']:<18s} {t['color']:<8s} at ({x:.3f}, {y:.3f}, {z:.3f}) {state} ({t['bin'] or 'none'})")
    sorted_ok = sum(o.result == "ok" for o in outcomes)
    elapsed = time.monotonic() - start
    print(
        f"{sorted_ok} sorted, {len(outcomes) - sorted_ok} failed attempts, "
        f"{len(truth) - len(misplaced)}/{len(truth)} objects in their bins, {elapsed:.1f} s"
    )
    if args.json:
        with open(args.json, "w", encoding="utf-8") as out:
            json.dump({"outcomes": [asdict(o) for o in outcomes], "truth": truth, "seconds": elapsed}, out, indent=1)
    return 0 if not misplaced and all(o.result == "ok" for o in outcomes) else 1


if __name__ == "__main__":
    sys.exit(main())
