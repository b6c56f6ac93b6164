#!/usr/bin/env python3
"""Packing from a running belt against a running stack (`make bench-pack`; scripts/bench_pack.sh starts the stack on
its world, bench/pack_world.yaml unless --world, in real time, with the two-finger gripper or with --tool suction the
suction variant, and runs this; --launch-file prints the tool's launch file and exits).

The belt and the box are the simulator's world's (its ~world parameter): --conveyor and --box name them, by default
its first conveyor and first bin. For each run (a belt speed and a number of objects) the belt is set to that speed
and the benchmark spawns the objects onto its upstream end (SPAWN_INSET from it) at seeded random intervals: boxes
and upright cylinders, 3-6 cm wide and high, random yaw (boxes) and lateral offset (up to LATERAL either side).
pack_objects.py packs them into the box (--pattern, --boxes enough for every object: a full box is checked and
emptied) and writes every arriving object's outcome. Each spawned object is accounted for: placed correctly (in its
slot within --tolerance and upright), misplaced, passed (rode past the last point it could be picked at, by the
belt's end, or off the belt, seen also while the arm was busy), its pick's failure class (missed, not grasped,
dropped, unreachable, failed, place failed), or still on the belt when packing stopped; the classes add up to the
objects spawned. Picks per minute are simulated time, from the start of packing to the last placement.

    bench/pack_bench.py --runs 0.2:100 0.1:10 0.3:10 --seed 1 --report report.md
    bench/pack_bench.py --tool suction --runs 0.2:100 --report report.md
"""

from __future__ import annotations

import argparse
import json
import math
import random
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections import Counter
from pathlib import Path

import numpy as np
import rospy
from geometry_msgs.msg import Pose
from shape_msgs.msg import SolidPrimitive
from sixdof_commander.sim_world import Bin, Conveyor, SimWorld, SimWorldError, wait_for_world
from sixdof_commander.transforms import matrix_from_quaternion
from std_msgs.msg import ColorRGBA

from sixdof_msgs.msg import SimObject
from sixdof_msgs.srv import DeleteObject, SetConveyor, SpawnObject

# m: arrivals are spawned this far in from the belt's upstream end, up to LATERAL either side of its centre line.
SPAWN_INSET, LATERAL = 0.05, 0.02
COLOURS = ((0.9, 0.1, 0.1), (0.1, 0.7, 0.2), (0.1, 0.3, 0.9), (0.95, 0.85, 0.1))
# The launch file (sixdof_bringup) of each tool, and its arrivals' default interval (s): a suction pick's cycle is
# shorter (the cup seals as it touches, where fingers take 1 s to close).
TOOLS = {"fingers": ("demo.launch", (6.0, 7.0)), "suction": ("demo_suction.launch", (2.5, 3.0))}
CLASSES = (
    "passed", "missed", "not grasped", "dropped", "unreachable", "failed", "place failed", "misplaced", "on belt"
)  # fmt: skip


class Belt:
    """Where arrivals go onto a conveyor: its upstream end's centre on the belt's top face, and the axis across it."""

    def __init__(self, conveyor: Conveyor) -> None:
        self.name = conveyor.name
        rotation = matrix_from_quaternion(conveyor.orientation)
        along = rotation[:, 0] if np.dot(conveyor.direction, rotation[:, 0]) > 0.0 else -rotation[:, 0]
        top = np.asarray(conveyor.position) + rotation[:, 2] * conveyor.size[2] / 2.0
        self.start = top - along * (conveyor.size[0] / 2.0 - SPAWN_INSET)
        self.across = np.cross(along, rotation[:, 2])


def random_object(rng: random.Random, name: str, belt: Belt) -> SimObject:
    shape = rng.choice(("box", "cylinder"))
    width, height = rng.uniform(0.03, 0.06), rng.uniform(0.03, 0.06)
    obj = SimObject(name=name, mass=0.05, friction=0.8, color=ColorRGBA(*rng.choice(COLOURS), 1.0))
    if shape == "box":
        depth = rng.uniform(0.03, 0.06)
        obj.shape = SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[width, depth, height])
    else:
        obj.shape = SolidPrimitive(type=SolidPrimitive.CYLINDER, dimensions=[height, width / 2.0])
    yaw = rng.uniform(-math.pi, math.pi) if shape == "box" else 0.0
    obj.pose = Pose()
    x, y, z = belt.start + belt.across * rng.uniform(-LATERAL, LATERAL) + [0.0, 0.0, height / 2.0 + 0.002]
    obj.pose.position.x, obj.pose.position.y, obj.pose.position.z = x, y, z
    obj.pose.orientation.z, obj.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return obj


def spawner(
    rng: random.Random, belt: Belt, prefix: str, count: int, interval: tuple[float, float], names: list[str]
) -> None:
    """Spawn `count` objects at random intervals (simulated seconds), appending their names."""
    spawn = rospy.ServiceProxy("sixdof_sim/spawn_object", SpawnObject)
    for i in range(count):
        if rospy.is_shutdown():
            return
        name = f"{prefix}_{i:03d}"
        response = spawn(random_object(rng, name, belt))
        if not response.success:
            rospy.logerr(f"spawning {name}: {response.status_message}")
        else:
            names.append(name)
        rospy.sleep(rng.uniform(*interval))


def run(args: argparse.Namespace, belt: Belt, box: Bin, speed: float, count: int, rng: random.Random) -> dict:
    set_conveyor = rospy.ServiceProxy("sixdof_sim/set_conveyor", SetConveyor)
    response = set_conveyor(belt.name, speed)
    if not response.success:
        raise RuntimeError(f"set_conveyor: {response.status_message}")
    names: list[str] = []
    prefix = f"v{round(speed * 100):02d}"
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "pack.json"
        command = [
            "rosrun", "sixdof_scripts", "pack_objects.py", "--box", box.name, "--conveyor", belt.name,
            "--pattern", args.pattern,
            "--boxes", str(count), "--objects", str(count), "--max-failures", str(count),
            "--timeout", str(count * max(args.interval) * 2.0 + 60.0), "--tolerance", str(args.tolerance),
            "--json", str(out), *args.pack_args,
        ]  # fmt: skip
        wall = time.monotonic()
        packer = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        rospy.sleep(2.0)  # pack_objects at home
        arrivals = (rng, belt, prefix, count, tuple(args.interval), names)
        thread = threading.Thread(target=spawner, args=arrivals, daemon=True)
        thread.start()
        log = packer.communicate()[0]
        wall = time.monotonic() - wall
        thread.join()
        if not out.exists():
            raise RuntimeError(f"pack_objects.py wrote no results (exit {packer.returncode}):\n{log}")
        result = json.loads(out.read_text())
    print(log, file=sys.stderr)
    outcomes = {o["name"]: o for o in result["outcomes"]}
    delete = rospy.ServiceProxy("sixdof_sim/delete_object", DeleteObject)
    for name in names:  # the last box's objects, and whatever else is left, for the next run
        delete(name)
    result.update(speed=speed, spawned=len(names), wall=wall, unaccounted=[n for n in names if n not in outcomes])
    return result


def percentile(values: list[float], q: float) -> float:
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, math.ceil(q * len(ordered)) - 1))]


def report(args: argparse.Namespace, world: SimWorld, results: list[dict]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    suction = args.tool == "suction"
    lines = [
        "## pack, suction (scripts/bench_pack.sh --tool suction)" if suction else "## pack (scripts/bench_pack.sh)",
        "",
        f"Run {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} at commit {commit or 'unknown'}: pack_objects.py "
        f"on the world '{world.name}', simulator in real time, seed {args.seed}, "
        f"{'the suction variant (demo_suction.launch)' if suction else 'the two-finger gripper (demo.launch)'}"
        f"{', pack_objects.py ' + ' '.join(args.pack_args) if args.pack_args else ''}.",
        f"Objects spawned onto the belt's upstream end every {args.interval[0]:g}-{args.interval[1]:g} s (simulated, "
        "seeded): boxes and upright cylinders 3-6 cm wide and high; packed",
        f"{args.pattern} into the world's box, which is checked and emptied when full. Placed correctly = in its slot "
        f"within {args.tolerance * 1000:.0f} mm and upright (10 deg).",
        "Runs with fewer than 100 objects are shorter for time, not chosen on their results.",
        "",
        "| belt speed | objects | placed correctly | picks per minute (simulated) | "
        + " | ".join(CLASSES)
        + " | place error median / p95 | wall time |",
        "|---" * (6 + len(CLASSES)) + "|",
    ]
    for r in results:
        counts = Counter({k: v for k, v in r["counts"].items()})
        good = counts.get("packed", 0)
        errors = [o["error_mm"] for o in r["outcomes"] if o["outcome"] == "packed" and "error_mm" in o]
        accounted = r["spawned"] - len(r["unaccounted"])
        lines.append(
            f"| {r['speed']:g} m/s | {r['spawned']} ({accounted} accounted for) | {good} "
            f"({100.0 * good / max(r['spawned'], 1):.1f} %) | {r['picks_per_minute']:.1f} | "
            + " | ".join(str(counts.get(k, 0)) for k in CLASSES)
            + f" | {statistics.median(errors) if errors else math.nan:.1f} / {percentile(errors, 0.95):.1f} mm"
            f" | {r['wall'] / 60.0:.1f} min |"
        )
    lines += [
        "",
        "Cycle of the placed objects (simulated s, median / p95): pick (the approach from the last place, "
        "the follow path and lift), place (to the slot and release), and from one placement to the next:",
        "",
    ]
    for r in results:
        placed = [o for o in r["outcomes"] if "pick_s" in o]
        gaps = [b["time"] - a["time"] for a, b in zip(placed, placed[1:], strict=False)]
        parts = [(what, [o[key] for o in placed]) for what, key in (("pick", "pick_s"), ("place", "place_s"))]
        if not placed:
            lines.append(f"- {r['speed']:g} m/s: none placed")
            continue
        lines.append(
            f"- {r['speed']:g} m/s: "
            + ", ".join(f"{what} {statistics.median(v):.2f} / {percentile(v, 0.95):.2f}" for what, v in parts if v)
            + (f", placement to placement {statistics.median(gaps):.2f} / {percentile(gaps, 0.95):.2f}" if gaps else "")
        )
    failures = [(r["speed"], o) for r in results for o in r["outcomes"] if o["outcome"] not in ("packed", "passed")]
    if failures:
        lines += ["", "Failures:", ""]
        for speed, o in failures:
            lines.append(f"- {speed:g} m/s, {o['name']} at {o['time']:.1f} s: {o['outcome']}: {o.get('message', '')}")
    unaccounted = [n for r in results for n in r["unaccounted"]]
    if unaccounted:
        lines += ["", f"Not accounted for by pack_objects.py: {', '.join(unaccounted)}"]
    return "\n".join(lines) + "\n"


def world_parts(world: SimWorld, args: argparse.Namespace) -> tuple[Belt, Bin]:
    """The conveyor and the bin of the world the run uses (--conveyor, --box: by default its first ones)."""
    conveyors = {c.name: c for c in world.conveyors}
    bins = {b.name: b for b in world.bins}
    conveyor = args.conveyor or next(iter(conveyors), "")
    box = args.box or next(iter(bins), "")
    if conveyor not in conveyors:
        raise SimWorldError(f"the world '{world.name}' has no conveyor '{conveyor}' (conveyors: {list(conveyors)})")
    if box not in bins:
        raise SimWorldError(f"the world '{world.name}' has no bin '{box}' (bins: {list(bins)})")
    return Belt(conveyors[conveyor]), bins[box]


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", nargs="+", default=["0.2:100", "0.1:10", "0.3:10"], help="SPEED:OBJECTS ...")
    parser.add_argument("--tool", choices=TOOLS, default="fingers", help="the stack's tool (fingers)")
    parser.add_argument("--launch-file", action="store_true", help="print the tool's launch file and exit")
    parser.add_argument("--interval", nargs=2, type=float, help="s between arrivals (fingers 6 7, suction 2.5 3)")
    parser.add_argument("--conveyor", default="", help="the world's conveyor objects arrive on (its first)")
    parser.add_argument("--box", default="", help="the world's bin to pack into (its first)")
    parser.add_argument("--pattern", default="2x2", help="pack_objects.py's --pattern (2x2)")
    parser.add_argument("--tolerance", type=float, default=0.005, help="m from the slot's centre (0.005)")
    parser.add_argument("--seed", type=int, default=1, help="random seed (1)")
    parser.add_argument("--pick-before", type=float, help="pack_objects.py's --pick-before (its default)")
    parser.add_argument("--approach", type=float, help="pack_objects.py's --approach (its default)")
    parser.add_argument("--report", help="write the markdown section here")
    args = parser.parse_args(argv)
    runs = []
    for text in args.runs:
        speed, _, count = text.partition(":")
        try:
            runs.append((float(speed), int(count)))
        except ValueError:
            parser.error(f"--runs takes SPEED:OBJECTS (e.g. 0.2:100), got '{text}'")
        if not (runs[-1][0] > 0.0 and runs[-1][1] > 0):
            parser.error(f"--runs: speed and objects must be > 0, got '{text}'")
    args.interval = args.interval or list(TOOLS[args.tool][1])
    if not 0.0 < args.interval[0] <= args.interval[1]:
        parser.error(f"--interval must be 0 < MIN <= MAX, got {args.interval}")
    args.run_list = runs
    chosen = [(name, getattr(args, name)) for name in ("pick_before", "approach") if getattr(args, name) is not None]
    args.pack_args = [f"--{name.replace('_', '-')}={value:g}" for name, value in chosen]
    return args


def main() -> int:
    args = parse_args(sys.argv[1:])
    if args.launch_file:
        print(TOOLS[args.tool][0])
        return 0
    rospy.init_node("pack_bench", anonymous=True)
    rospy.wait_for_service("sixdof_sim/spawn_object", timeout=120.0)
    try:
        world = wait_for_world()
        belt, box = world_parts(world, args)
    except SimWorldError as err:
        print(f"pack_bench.py: error: {err}", file=sys.stderr)
        return 2
    rng = random.Random(args.seed)
    results = []
    for speed, count in args.run_list:
        print(f"[bench-pack] {count} objects at {speed:g} m/s", flush=True)
        results.append(run(args, belt, box, speed, count, rng))
        print(report(args, world, results[-1:]), flush=True)
    text = report(args, world, results)
    print(text)
    if args.report:
        Path(args.report).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
