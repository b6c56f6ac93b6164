#!/usr/bin/env python3
"""Pack arriving objects into a box: pick each object a conveyor brings (sixdof_commander.moving_pick.pick_moving,
on the fly) and place it upright in the next free slot of the box, printing each pick's outcome and the picks per
minute (simulated time). The box is a bin of the simulator's world (its ~world parameter, `bins:`). The slots come
from --pattern ROWSxCOLUMNS[xLAYERS] (the box's inside cut into equal cells, rows along the bin's x axis, layers
--layer-height apart) or --pattern-file, a pallet-style YAML (sixdof_commander.pack_pattern: rows, columns, layers,
spacing, layer_height). Arriving objects are the simulator's (its object states and velocities): the dynamic
objects resting on the conveyor's belt. Every arriving object is accounted for: packed, failed (by class), passed
(it rode past the last point it could be picked at, --pick-before, or off the belt, watched also while the arm is
busy), or still on the belt when the run stopped.

    rosrun sixdof_scripts pack_objects.py --box box --pattern 2x2      (with the stack on a conveyor world)

With --boxes N the box is filled N times: a full box's contents are checked and then removed from the world (as if
the full box were swapped for an empty one). --objects N stops once N arriving objects are accounted for.

Exit codes: 0 every slot filled with its object upright in it, 1 not (too many failed picks, the time ran out, or an
object not in its slot), 2 bad arguments or pattern file, a missing node, or a world without that box or a conveyor.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

import rospy
from sixdof_commander import ArmDriver, SixdofCommanderError
from sixdof_commander.pack_pattern import Pattern, PatternError, Slot, load_pattern, parse_pattern
from sixdof_commander.packing import RETREAT_AFTER, Packer
from sixdof_commander.sim_world import WORLD_PARAMETER, Bin, Conveyor, SimWorldError, wait_for_world

PASSED = "passed"
APPROACH, SUCTION_APPROACH = 0.05, 0.03  # m, --approach's defaults
ON_BELT = "on belt"


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--box", required=True, help="the bin of the world to fill")
    patterns = parser.add_mutually_exclusive_group()
    patterns.add_argument("--pattern", default="2x2", help="ROWSxCOLUMNS[xLAYERS] slots (default 2x2)")
    patterns.add_argument("--pattern-file", default="", help="a pattern YAML (rows, columns, layers, spacing, ...)")
    parser.add_argument("--layer-height", type=float, default=0.065, help="m between --pattern's layers (0.065)")
    parser.add_argument("--boxes", type=int, default=1, help="boxes to fill, one after the other (1)")
    parser.add_argument("--objects", type=int, default=0, help="stop after this many arriving objects (0: no limit)")
    parser.add_argument("--conveyor", default="", help="the conveyor objects arrive on (default: the world's first)")
    parser.add_argument("--timeout", type=float, default=300.0, help="simulated seconds to fill the boxes (300)")
    parser.add_argument("--max-failures", type=int, default=3, help="failed picks before giving up (3)")
    parser.add_argument(
        "--pick-before",
        type=float,
        default=-0.15,
        help="m along the belt from its centre: an object past it is left to ride on (default -0.15)",
    )
    parser.add_argument("--tolerance", type=float, default=0.015, help="m an object may rest from its slot (0.015)")
    parser.add_argument("--velocity-scaling", type=float, default=1.0, help="max velocity scaling in (0, 1] (1.0)")
    parser.add_argument(
        "--approach",
        type=float,
        help=f"m above objects and slots to descend from ({APPROACH:g}; a suction cup, which has nothing to clear but "
        f"its own face, {SUCTION_APPROACH:g})",
    )
    parser.add_argument("--json", default="", help="write every object's outcome and the totals to this file")
    parser.add_argument("--ns", default="", help="namespace of the planner and simulator nodes")
    args = parser.parse_args(argv)
    for name in ("timeout", "tolerance", "layer_height", "approach"):
        value = getattr(args, name)
        if value is None:
            continue
        if not math.isfinite(value) or value <= 0.0:
            parser.error(f"--{name.replace('_', '-')} must be > 0, got {value}")
    if not math.isfinite(args.pick_before):
        parser.error(f"--pick-before must be a finite number, got {args.pick_before}")
    for name, least in (("max_failures", 0), ("boxes", 1), ("objects", 0)):
        if getattr(args, name) < least:
            parser.error(f"--{name.replace('_', '-')} must be >= {least}, got {getattr(args, name)}")
    if not 0.0 < args.velocity_scaling <= 1.0:
        parser.error(f"--velocity-scaling must be in (0, 1], got {args.velocity_scaling}")
    try:
        if args.pattern_file:
            args.slots_pattern = load_pattern(args.pattern_file)
        else:
            args.slots_pattern = parse_pattern(args.pattern, args.layer_height)
    except PatternError as err:
        # One line, as every bad-input message of a pattern (argparse's own errors add a usage line).
        print(
            f"pack_objects.py: error: {'--pattern-file' if args.pattern_file else '--pattern'}: {err}", file=sys.stderr
        )
        sys.exit(2)
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


class Run:
    """Every arriving object's outcome, the boxes filled so far, and the picks per minute."""

    def __init__(self, packer: Packer, args: argparse.Namespace, slots: list[Slot]) -> None:
        self.packer, self.args, self.slots = packer, args, slots
        self.start = rospy.get_time()
        self.outcomes: dict[str, dict] = {}
        self.in_box: list[str] = []
        self.boxes = 0
        self.last_placed = self.start

    def failures(self) -> dict[str, int]:
        counts: dict[str, int] = {}
        for outcome in self.outcomes.values():
            if outcome["outcome"] not in ("packed", "misplaced", PASSED, ON_BELT):
                counts[outcome["outcome"]] = counts.get(outcome["outcome"], 0) + 1
        return counts

    def watch_belt(self) -> None:
        """The objects the packer saw pass (it watches the belt also while the arm is busy)."""
        for name, (stamp, how) in list(self.packer.passed.items()):
            if name not in self.outcomes:
                self.outcomes[name] = {"name": name, "outcome": PASSED, "message": how, "time": stamp - self.start}

    def stop(self) -> None:
        """At the end: the objects still on the belt, neither picked nor passed (the run stopped first)."""
        self.watch_belt()
        for name in self.packer.seen - set(self.outcomes):
            self.outcomes[name] = {"name": name, "outcome": ON_BELT, "time": rospy.get_time() - self.start}

    def finished(self) -> bool:
        args = self.args
        if self.boxes >= args.boxes or rospy.is_shutdown():
            return True
        if args.objects and len(self.outcomes) >= args.objects:
            return True
        return rospy.get_time() - self.start > args.timeout or sum(self.failures().values()) > args.max_failures

    def pack_next(self) -> None:
        name = self.packer.take_next()
        if name is None:
            self.packer.idle(RETREAT_AFTER)
            time.sleep(0.02)
            return
        slot = self.slots[len(self.in_box)]
        result = self.packer.pack(name, slot)
        now = rospy.get_time() - self.start
        if not result.ok:
            self.outcomes[name] = {"name": name, "outcome": result.failure, "message": result.message, "time": now}
            print(f"  {name}: {result.failure}: {result.message}", flush=True)
            return
        self.outcomes[name] = {"name": name, "outcome": "packed", "box": self.boxes, "slot": len(self.in_box)}
        pick, place = self.packer.durations
        self.outcomes[name].update(slot=[slot.x, slot.y, slot.layer], time=now, pick_s=pick, place_s=place)
        self.in_box.append(name)
        self.last_placed = rospy.get_time()
        print(
            f"  box {self.boxes + 1} slot {len(self.in_box)}/{len(self.slots)}: {name} at ({slot.x:.3f}, "
            f"{slot.y:.3f}, layer {slot.layer}), {now:.1f} s, {self.placed() / (now / 60.0):.1f} picks/min",
            flush=True,
        )
        if len(self.in_box) == len(self.slots):
            self.close_box(swap=self.boxes + 1 < self.args.boxes)

    def placed(self) -> int:
        return sum(o["outcome"] in ("packed", "misplaced") for o in self.outcomes.values())

    def close_box(self, swap: bool) -> None:
        """Check the box's objects against their slots; with swap, remove them for the next box."""
        for name, slot in zip(self.in_box, self.slots, strict=False):
            check = self.packer.check(name, slot, self.args.tolerance)
            outcome = self.outcomes[name]
            outcome.update(error_mm=round(check.error * 1000.0, 2), lean_deg=round(math.degrees(check.lean), 2))
            if not check.ok:
                outcome["outcome"] = "misplaced"
                print(
                    f"  {name} is not upright in its slot: {check.error * 1000:.1f} mm off, leaning "
                    f"{math.degrees(check.lean):.1f} deg",
                    flush=True,
                )
            if swap:
                self.packer.delete(name)
        self.boxes += 1
        self.in_box = []

    def summary(self) -> dict:
        elapsed = self.last_placed - self.start
        placed = self.placed()
        counts: dict[str, int] = {}
        for outcome in self.outcomes.values():
            counts[outcome["outcome"]] = counts.get(outcome["outcome"], 0) + 1
        return {
            "objects": len(self.outcomes),
            "counts": counts,
            "packed": counts.get("packed", 0),
            "boxes": self.boxes,
            "seconds": elapsed,
            "picks_per_minute": placed / (elapsed / 60.0) if placed and elapsed > 0.0 else 0.0,
            "outcomes": sorted(self.outcomes.values(), key=lambda o: o["time"]),
            "belt_speed": [(t - self.start, v) for t, v in self.packer.speeds if t >= self.start],
        }


def main() -> int:
    args = parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("pack_objects", anonymous=True)
    pattern: Pattern = args.slots_pattern
    try:
        box, conveyor = world_parts(args)
        slots = pattern.slots(box)
        scaling = args.velocity_scaling
        driver = ArmDriver(ns=args.ns, velocity_scaling=scaling, acceleration_scaling=scaling)
        driver.approach_distance = args.approach or (SUCTION_APPROACH if driver.suction else APPROACH)
        packer = Packer(driver, conveyor, box, pick_before=args.pick_before)
    except (SixdofCommanderError, SimWorldError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print(
        f"packing {len(slots)} slots ({pattern.rows}x{pattern.columns}x{pattern.layers}) into '{box.name}' "
        f"from '{conveyor.name}', {args.boxes} box(es)",
        flush=True,
    )
    if not driver.moveto_named(driver.home):
        print(f"error: moving home failed: {driver.last_failure}", file=sys.stderr)
        return 1
    run = Run(packer, args, slots)
    while not run.finished():
        run.watch_belt()
        run.pack_next()
    run.stop()
    if run.in_box:
        run.close_box(swap=False)
    packer.idle()
    driver.moveto_named(driver.home)
    summary = run.summary()
    if args.json:
        with open(args.json, "w") as out:
            json.dump(summary, out, indent=1)
    counts = ", ".join(f"{k} {v}" for k, v in sorted(summary["counts"].items()))
    print(
        f"packed {summary['packed']}/{len(slots) * args.boxes} in {summary['seconds']:.1f} s (simulated): "
        f"{summary['picks_per_minute']:.1f} picks per minute; objects: {counts or 'none'}",
        flush=True,
    )
    return 0 if summary["packed"] == len(slots) * args.boxes else 1


if __name__ == "__main__":
    sys.exit(main())
