#!/usr/bin/env python3
"""Vision-based sorting benchmark against a running stack with the perception node (`make bench-sort`;
scripts/bench_sort.sh starts the stack on sixdof_sim/worlds/sorting.yaml and runs this).

Each layout (seeded) empties the table (deletes every dynamic object), spawns 3-6 objects of the bins' colours
(cubes, upright cylinders, spheres; 3-6 cm; random positions at least --min-separation apart, random yaw),
moves the arm to its home pose and then:
  detection  every object is matched to the nearest detection of a frame taken after the spawn (within 3 cm):
             position error of the centre, colour class right or wrong, missed objects, phantom detections;
  sorting    sort_objects.py runs on the layout; an object succeeds when it rests in its colour's bin. Each
             failure is classified by the script's outcome for that object (unreachable, grasp_missed, ...) or
             as 'not_attempted' (never picked) or 'dropped' (the script reported ok, the object is not in the bin).
The report is the "## sort" section of bench/results.md ("## sort with depth noise" when the camera's depth is
noisy: scripts/bench_sort.sh --depth-noise SIGMA gives the world's cameras that noise and passes it on here).

    bench/sort_bench.py --layouts 10 --seed 1 --report report.md
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter

import rospy
from geometry_msgs.msg import Pose
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import ArmDriver
from sixdof_commander.colors import color_class
from sixdof_commander.sim_world import wait_for_world
from std_msgs.msg import ColorRGBA

from sixdof_msgs.msg import DetectedObjectArray, ObjectStates, SimObject
from sixdof_msgs.srv import DeleteObject, GetObjectState, SpawnObject

SHAPES = ("cube", "cylinder", "sphere")


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    if not ordered:
        return math.nan
    k = (len(ordered) - 1) * q
    lo, hi = math.floor(k), math.ceil(k)
    return ordered[lo] + (ordered[hi] - ordered[lo]) * (k - lo)


class Bench:
    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.rng = random.Random(args.seed)
        self.bins = wait_for_world().bins
        self.bin_rgb_by_class: dict[str, tuple[float, float, float]] = {}
        self.driver = ArmDriver(velocity_scaling=0.5, acceleration_scaling=0.5)
        for service in ("spawn_object", "delete_object", "get_object_state"):
            rospy.wait_for_service(f"sixdof_sim/{service}", timeout=120.0)
        self.spawn = rospy.ServiceProxy("sixdof_sim/spawn_object", SpawnObject)
        self.delete = rospy.ServiceProxy("sixdof_sim/delete_object", DeleteObject)
        self.get_state = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
        self.errors_mm: list[float] = []
        self.colour_right = 0
        self.colour_total = 0
        self.missed = 0
        self.phantoms = 0
        self.objects = 0
        self.sorted_ok = 0
        self.failures: Counter = Counter()
        self.failure_lines: list[str] = []
        self.sort_seconds = 0.0
        self.layouts_done = 0

    def clear(self) -> None:
        states = rospy.wait_for_message("sixdof_sim/object_states", ObjectStates, timeout=30.0)
        for name in states.name:
            if not self.get_state(name).object.is_static:
                self.delete(name)

    def layout(self, index: int) -> list[SimObject]:
        xmin, xmax, ymin, ymax = self.args.region
        count = self.rng.randint(3, 6)
        placed: list[tuple[float, float]] = []
        objects = []
        colours = sorted(self.bin_rgb_by_class)
        for i in range(count):
            for _ in range(1000):
                x, y = self.rng.uniform(xmin, xmax), self.rng.uniform(ymin, ymax)
                clear_of_bins = all(not b.contains(x, y) and math.dist((x, y), b.centre[:2]) > 0.14 for b in self.bins)
                if clear_of_bins and all(math.dist((x, y), p) >= self.args.min_separation for p in placed):
                    break
            else:
                break
            placed.append((x, y))
            shape = self.rng.choice(SHAPES)
            colour = self.rng.choice(colours)
            primitive = SolidPrimitive()
            if shape == "cube":
                edge = self.rng.uniform(0.03, 0.05)
                primitive.type, primitive.dimensions = SolidPrimitive.BOX, [edge, edge, edge]
                half = edge / 2.0
            elif shape == "cylinder":
                height, radius = self.rng.uniform(0.03, 0.06), self.rng.uniform(0.015, 0.025)
                primitive.type, primitive.dimensions = SolidPrimitive.CYLINDER, [height, radius]
                half = height / 2.0
            else:
                radius = self.rng.uniform(0.02, 0.03)
                primitive.type, primitive.dimensions = SolidPrimitive.SPHERE, [radius]
                half = radius
            yaw = self.rng.uniform(-math.pi, math.pi) if shape == "cube" else 0.0
            pose = Pose()
            pose.position.x, pose.position.y, pose.position.z = x, y, half
            pose.orientation.z, pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
            objects.append(
                SimObject(
                    name=f"sort{index}_{i}_{colour}_{shape}",
                    shape=primitive,
                    pose=pose,
                    mass=0.08,
                    friction=0.8,
                    color=ColorRGBA(*self.bin_rgb_by_class[colour], 1.0),
                )
            )
        return objects

    def truth(self) -> dict:
        states = rospy.wait_for_message("sixdof_sim/object_states", ObjectStates, timeout=30.0)
        out = {}
        for name, pose in zip(states.name, states.pose, strict=True):
            obj = self.get_state(name).object
            if not obj.is_static:
                out[name] = (
                    (pose.position.x, pose.position.y, pose.position.z),
                    color_class(obj.color.r, obj.color.g, obj.color.b),
                )
        return out

    def frame_after(self, stamp: rospy.Time) -> DetectedObjectArray:
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline:
            msg = rospy.wait_for_message("detected_objects", DetectedObjectArray, timeout=120.0)
            if msg.header.stamp > stamp:
                return msg
        raise RuntimeError("no detected_objects frame after the layout was spawned")

    def measure_detection(self, index: int) -> None:
        truth = self.truth()
        # Two frames: the tracker has seen the layout once before the measured frame.
        self.frame_after(rospy.Time.now() + rospy.Duration(0.5))
        frame = self.frame_after(rospy.Time.now())
        used = set()
        for name, (position, colour) in truth.items():
            best, best_d = None, 0.03
            for o in frame.objects:
                p = o.pose.pose.position
                d = math.dist(position, (p.x, p.y, p.z))
                if o.id not in used and d < best_d:
                    best, best_d = o, d
            if best is None:
                self.missed += 1
                self.failure_lines.append(f"layout {index}: {name} not detected")
                continue
            used.add(best.id)
            self.errors_mm.append(best_d * 1000.0)
            self.colour_total += 1
            self.colour_right += best.color == colour
        self.phantoms += len([o for o in frame.objects if o.id not in used])

    def sort(self, index: int) -> None:
        with tempfile.TemporaryDirectory() as tmp:
            result_file = os.path.join(tmp, "sort.json")
            start = time.monotonic()
            run = subprocess.run(
                ["rosrun", "sixdof_scripts", "sort_objects.py", "--json", result_file],
                capture_output=True,
                text=True,
                timeout=self.args.sort_timeout,
                check=False,
            )
            self.sort_seconds += time.monotonic() - start
            if not os.path.exists(result_file):
                self.failure_lines.append(
                    f"layout {index}: sort_objects.py exit {run.returncode}: "
                    f"{(run.stderr or run.stdout).strip().splitlines()[-1:]}"
                )
                return
            with open(result_file, encoding="utf-8") as stream:
                result = json.load(stream)
        outcomes = result["outcomes"]
        for t in result["truth"]:
            self.objects += 1
            if t["in_bin"]:
                self.sorted_ok += 1
                continue
            # The script's last outcome for an object that started where this one started... objects moved, so
            # match by colour and the last attempt's failure when one exists.
            failed = [o for o in outcomes if o["result"] != "ok" and o["label"].startswith(t["color"])]
            if failed:
                kind = failed[-1]["result"]
                detail = failed[-1]["detail"]
            elif any(o["label"].startswith(t["color"]) for o in outcomes):
                kind, detail = "dropped", "placed but not resting in its bin"
            else:
                kind, detail = "not_attempted", "never picked (not detected or skipped)"
            self.failures[kind] += 1
            self.failure_lines.append(
                f"layout {index}: {t['name']} ({t['color']}) at "
                f"({t['position'][0]:.3f}, {t['position'][1]:.3f}): {kind}: {detail}"
            )

    def run(self) -> None:
        self.bin_rgb_by_class = {b.color: b.rgb for b in self.bins}
        end = time.monotonic() + self.args.max_minutes * 60.0
        for index in range(self.args.layouts):
            if time.monotonic() > end:
                break
            self.clear()
            self.driver.moveto_named(self.args.home or self.driver.home)
            for obj in self.layout(index):
                response = self.spawn(obj)
                if not response.success:
                    raise RuntimeError(f"spawning {obj.name}: {response.status_message}")
            rospy.sleep(0.5)
            self.measure_detection(index)
            self.sort(index)
            self.layouts_done += 1
            print(
                f"layout {index}: {self.sorted_ok}/{self.objects} objects sorted so far, "
                f"{self.missed} missed, {self.phantoms} phantoms",
                flush=True,
            )

    def report(self) -> str:
        errors = self.errors_mm
        noise = self.args.depth_noise
        depth = (
            f"the camera's depth with Gaussian noise of {noise * 1000.0:g} mm (standard deviation)"
            if noise > 0.0
            else "noise-free depth"
        )
        lines = [
            "## sort with depth noise (scripts/bench_sort.sh)" if noise > 0.0 else "## sort (scripts/bench_sort.sh)",
            "",
            f"Run {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, seed {self.args.seed}: "
            f"{self.layouts_done} random layouts of 3-6 objects (of {self.args.layouts} asked; the run stops after "
            f"{self.args.max_minutes:g} minutes), sixdof_sim/worlds/sorting.yaml with {depth}, headless stack "
            "with the perception node (no ground truth in the planning scene).",
            "",
            "| figure | value |",
            "| --- | --- |",
            f"| detection position error, median | {statistics.median(errors) if errors else math.nan:.2f} mm |",
            f"| detection position error, p95 | {percentile(errors, 0.95):.2f} mm |",
            f"| detection position error, max | {max(errors) if errors else math.nan:.2f} mm |",
            f"| colour class right | {self.colour_right}/{self.colour_total} |",
            f"| missed objects | {self.missed} |",
            f"| phantom detections | {self.phantoms} |",
            f"| objects sorted into their bin | {self.sorted_ok}/{self.objects} "
            f"({100.0 * self.sorted_ok / max(1, self.objects):.1f}%) |",
            f"| wall-clock seconds per object (sort_objects.py) | {self.sort_seconds / max(1, self.objects):.1f} s |",
        ]
        if self.failures:
            lines += ["", "Failures by class: " + ", ".join(f"{k} {v}" for k, v in self.failures.most_common()) + "."]
        if self.failure_lines:
            lines += ["", "```"] + self.failure_lines + ["```"]
        return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--layouts", type=int, default=50, help="random layouts (default 50)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--max-minutes", type=float, default=60.0, help="stop starting layouts after this long")
    parser.add_argument(
        "--region",
        type=float,
        nargs=4,
        default=[0.30, 0.52, -0.20, 0.14],
        metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
        help="where objects are spawned (m)",
    )
    parser.add_argument("--min-separation", type=float, default=0.09, help="between object centres (m)")
    parser.add_argument("--home", help="named state of the arm (default: the arm group's first SRDF state)")
    parser.add_argument("--sort-timeout", type=float, default=900.0, help="wall seconds per sort_objects.py run")
    parser.add_argument("--report", default="", help="write the report section (markdown) to this file")
    parser.add_argument(
        "--depth-noise",
        type=float,
        default=0.0,
        help="m: the depth noise the world's camera was given (scripts/bench_sort.sh sets it); only reported",
    )
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    if args.layouts < 1:
        parser.error("--layouts must be >= 1")
    if not (math.isfinite(args.depth_noise) and args.depth_noise >= 0.0):
        parser.error(f"--depth-noise must be >= 0 (m), got {args.depth_noise}")
    rospy.init_node("sort_bench", anonymous=True)
    bench = Bench(args)
    try:
        bench.run()
    finally:
        report = bench.report()
        print(report)
        if args.report:
            with open(args.report, "w", encoding="utf-8") as out:
                out.write(report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
