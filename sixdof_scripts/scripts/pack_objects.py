#!/usr/bin/env python3
"""Pack arriving objects into a box: pick each object a conveyor brings (sixdof_commander.moving_pick.pick_moving,
on the fly) and place it upright in the next free slot of the box, row by row, printing each pick's outcome and the
picks per minute (simulated time). The box is a bin of the simulator's world (its ~world parameter, `bins:`); the
pattern ROWSxCOLUMNS divides its inside into equal slots (rows along the bin's x axis). Arriving objects are the
simulator's (its object states and velocities): the dynamic objects resting on the conveyor's belt.

    rosrun sixdof_scripts pack_objects.py --box box --pattern 2x2      (with the stack on a conveyor world)

Exit codes: 0 every slot filled with its object upright in it, 1 not (too many failed picks, the time ran out, or an
object not in its slot), 2 bad arguments, a missing node, or a world without that box or a conveyor.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time

import numpy as np
import rospy
from sixdof_commander import ArmDriver, SixdofCommanderError
from sixdof_commander.moving_pick import pick_moving
from sixdof_commander.sim_world import WORLD_PARAMETER, Bin, Conveyor, SimWorldError, wait_for_world
from sixdof_commander.transforms import matrix_from_pose, matrix_from_quaternion

from sixdof_msgs.msg import ObjectStates

PATTERN = re.compile(r"^([1-9][0-9]*)x([1-9][0-9]*)$")


def slots(box: Bin, rows: int, columns: int) -> list[tuple[float, float]]:
    """Slot centres (world x, y), row by row: the bin's inside cut into rows x columns equal cells."""
    hx, hy = box.inner_half()
    return [
        box.to_world(-hx + (2 * r + 1) * hx / rows, -hy + (2 * c + 1) * hy / columns)
        for r in range(rows)
        for c in range(columns)
    ]


class Packer:
    def __init__(self, driver: ArmDriver, conveyor: Conveyor, ns: str) -> None:
        self.driver = driver
        self.conveyor = conveyor
        self.direction = np.asarray(conveyor.direction)
        self.states: ObjectStates | None = None
        self.done: set[str] = set()
        topic = f"{ns.rstrip('/')}/sixdof_sim/object_states" if ns else "sixdof_sim/object_states"
        rospy.Subscriber(topic, ObjectStates, self._on_states, queue_size=1)

    def _on_states(self, msg: ObjectStates) -> None:
        self.states = msg

    def on_belt(self, position: np.ndarray) -> float | None:
        """How far along the belt (m from its centre, downstream positive) an object resting on it is; None off it."""
        centre = np.asarray(self.conveyor.position)
        rotation = matrix_from_quaternion(self.conveyor.orientation)
        local = rotation.T @ (position - centre)
        half = np.asarray(self.conveyor.size) / 2.0
        if abs(local[0]) > half[0] or abs(local[1]) > half[1] or not half[2] < local[2] < half[2] + 0.1:
            return None
        return float(local[0]) if self.direction @ rotation[:, 0] > 0.0 else -float(local[0])

    def next_object(self, pick_before: float) -> str | None:
        """The object furthest downstream on the belt that is still upstream of pick_before."""
        states = self.states
        if states is None:
            return None
        best, best_along = None, -math.inf
        for name, pose, holder in zip(states.name, states.pose, states.attached_to, strict=True):
            if holder or name in self.done or name == self.conveyor.name:
                continue
            along = self.on_belt(np.array([pose.position.x, pose.position.y, pose.position.z]))
            if along is not None and best_along < along < pick_before:
                best, best_along = name, along
        return best


def put_down(driver: ArmDriver, name: str, slot: tuple[float, float]) -> bool:
    """Place the held object in its slot and retreat. Opening fingers may stop at a neighbour or the box's wall, or on
    the object while the grasp fix still holds it (it lets go within a few of its 4 Hz updates): the object is put
    down when the grasp fix has let it go."""
    if not driver.release_at(list(slot)):
        if not driver.last_failure.startswith("gripper did not open"):
            return False
        rospy.sleep(0.5)
        if driver.get_object_state(name).attached_to:
            return False
        if name in driver.scene.get_attached_object_names() and not driver.scene.detach_object(name):
            rospy.logwarn("detaching '%s' in the planning scene failed", name)
        driver.forget_held()
    return driver.retreat()


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--box", required=True, help="the bin of the world to fill")
    parser.add_argument("--pattern", default="2x2", help="ROWSxCOLUMNS slots (default 2x2)")
    parser.add_argument("--conveyor", default="", help="the conveyor objects arrive on (default: the world's first)")
    parser.add_argument("--timeout", type=float, default=300.0, help="simulated seconds to fill the box (300)")
    parser.add_argument("--max-failures", type=int, default=3, help="failed picks before giving up (3)")
    parser.add_argument(
        "--pick-before",
        type=float,
        default=-0.15,
        help="m along the belt from its centre: an object past it is left to ride on (default -0.15)",
    )
    parser.add_argument("--tolerance", type=float, default=0.015, help="m an object may rest from its slot (0.015)")
    parser.add_argument("--velocity-scaling", type=float, default=0.8, help="max velocity scaling in (0, 1]")
    parser.add_argument("--ns", default="", help="namespace of the planner and simulator nodes")
    args = parser.parse_args(argv)
    match = PATTERN.match(args.pattern)
    if match is None:
        parser.error(f"--pattern must be ROWSxCOLUMNS (e.g. 2x2), got '{args.pattern}'")
    args.rows, args.columns = int(match.group(1)), int(match.group(2))
    for name in ("timeout", "tolerance"):
        value = getattr(args, name)
        if not math.isfinite(value) or value <= 0.0:
            parser.error(f"--{name} must be > 0, got {value}")
    if not math.isfinite(args.pick_before):
        parser.error(f"--pick-before must be a finite number, got {args.pick_before}")
    if args.max_failures < 0:
        parser.error(f"--max-failures must be >= 0, got {args.max_failures}")
    if not 0.0 < args.velocity_scaling <= 1.0:
        parser.error(f"--velocity-scaling must be in (0, 1], got {args.velocity_scaling}")
    return args


def world_parts(args: argparse.Namespace) -> tuple[Bin, Conveyor]:
    world = wait_for_world(f"{args.ns.rstrip('/')}/{WORLD_PARAMETER}" if args.ns else WORLD_PARAMETER)
    box = next((b for b in world.bins if b.name == args.box), None)
    if box is None:
        bins = [b.name for b in world.bins]
        raise SixdofCommanderError(f"the world '{world.name}' has no box (bin) '{args.box}' (bins: {bins})")
    if not world.conveyors:
        raise SixdofCommanderError(f"the world '{world.name}' has no conveyor")
    wanted = args.conveyor or world.conveyors[0].name
    conveyor = next((c for c in world.conveyors if c.name == wanted), None)
    if conveyor is None:
        raise SixdofCommanderError(f"the world '{world.name}' has no conveyor '{args.conveyor}'")
    return box, conveyor


def main() -> int:
    args = parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("pack_objects", anonymous=True)
    try:
        box, conveyor = world_parts(args)
        rows, columns = args.rows, args.columns
        targets = slots(box, rows, columns)
        scaling = args.velocity_scaling
        driver = ArmDriver(ns=args.ns, velocity_scaling=scaling, acceleration_scaling=scaling)
        packer = Packer(driver, conveyor, args.ns)
    except (SixdofCommanderError, SimWorldError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print(f"packing {rows}x{columns} into '{box.name}' from '{conveyor.name}'", flush=True)
    if not driver.moveto_named(driver.home):
        print(f"error: moving home failed: {driver.last_failure}", file=sys.stderr)
        return 1
    start = rospy.get_time()
    placed: list[tuple[str, tuple[float, float], float]] = []
    failures: dict[str, int] = {}
    while len(placed) < len(targets) and not rospy.is_shutdown():
        elapsed = rospy.get_time() - start
        if elapsed > args.timeout or sum(failures.values()) > args.max_failures:
            break
        name = packer.next_object(args.pick_before)
        if name is None:
            time.sleep(0.05)
            continue
        packer.done.add(name)
        result = pick_moving(driver, name)
        if not result.ok:
            failures[result.failure] = failures.get(result.failure, 0) + 1
            print(f"  {name}: {result.failure}: {result.message}", flush=True)
            driver.gripper_open()
            driver.forget_held()
            driver.moveto_named(driver.home)
            continue
        x, y = targets[len(placed)]
        if not put_down(driver, name, (x, y)):
            failures["place failed"] = failures.get("place failed", 0) + 1
            print(f"  {name}: place failed: {driver.last_failure}", flush=True)
            driver.gripper_open()
            driver.forget_held()
            driver.moveto_named(driver.home)
            continue
        placed.append((name, (x, y), rospy.get_time()))
        minutes = (rospy.get_time() - start) / 60.0
        print(
            f"  slot {len(placed)}/{len(targets)}: {name} at ({x:.3f}, {y:.3f}), {rospy.get_time() - start:.1f} s, "
            f"{len(placed) / minutes:.1f} picks/min",
            flush=True,
        )
    driver.moveto_named(driver.home)
    rospy.sleep(0.5)
    in_slot = 0
    for name, (x, y), _ in placed:
        state = driver.get_object_state(name).object.pose
        upright = abs(matrix_from_pose(state)[2, 2]) > math.cos(math.radians(10.0))
        ok = math.dist((state.position.x, state.position.y), (x, y)) <= args.tolerance and upright
        in_slot += ok
        if not ok:
            print(f"  {name} is not upright in its slot ({state.position.x:.3f}, {state.position.y:.3f})", flush=True)
    elapsed = placed[-1][2] - start if placed else rospy.get_time() - start
    rate = len(placed) / (elapsed / 60.0) if elapsed > 0.0 and placed else 0.0
    failed = ", ".join(f"{k} {v}" for k, v in sorted(failures.items())) or "none"
    print(
        f"packed {in_slot}/{len(targets)} in {elapsed:.1f} s (simulated): {rate:.1f} picks per minute; "
        f"failures: {failed}",
        flush=True,
    )
    return 0 if in_slot == len(targets) else 1


if __name__ == "__main__":
    sys.exit(main())
