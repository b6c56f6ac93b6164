#!/usr/bin/env python3
"""Randomized pick and place against a running stack (`make bench-pick`, `make soak`; scripts/bench_pick.sh
starts the stack and runs this).

Each trial spawns one object in the simulator (a cube, an upright cylinder or a sphere, 3-6 cm, at a random
position and yaw inside --region), waits until the planning scene has it, picks it through the paper's stages
(ArmDriver: grasp, lift, release_at, retreat) and puts it down at a random free target of the same region.
A trial succeeds when the released object rests within --tolerance of the target and, a cube or cylinder, within
--tilt of upright (a sphere has no upright: its orientation is not checked).
Every failure is classified:
  planning     a motion could not be planned (or executed)
  unreachable  no top-down grasp or place at that spot (ArmDriver's UNREACHABLE: the object does not fit the
               gripper, or the arm cannot reach the pose above it or descend straight to it without collision)
  gripper      the gripper did not open, or did not close, within its goal (ArmDriver's GRIPPER)
  grasp        the gripper closed but the object was not held when lifted
  slip       the object was held after lifting but was lost before it was released
  place      the object was released but came to rest off the target (or tilted)
  cleanup    the trial succeeded but the gripper or arm could not be brought back afterwards
The object is deleted after each trial, so each trial starts from the same empty table. The robot is the running
stack's (any config package: `scripts/bench_pick.sh --config PKG`): its arm, gripper and home state come from the
package through move_group (ArmDriver).

With --rss, every ROS node's resident set size is sampled after each trial (the soak): the report gives each
node's growth from the end of the warm-up to the end, and the run fails when any grows by more than
--max-growth-mb. --rss-series FILE also writes every sample (CSV: trial, node, RSS in kB), to see whether a growth
levels off or keeps on.

    bench/pick_bench.py --trials 100 --seed 1 --report report.md
    bench/pick_bench.py --seed 1 --only 35 220     # replay trials 35 and 220 of that sequence
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
import subprocess
import sys
import time
import xmlrpc.client
from collections import Counter
from dataclasses import dataclass, field

import rosgraph
import rospy
from geometry_msgs.msg import Pose
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import ArmDriver, SixdofCommanderError
from sixdof_commander.straight_moves import GRIPPER, UNREACHABLE
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty

from sixdof_bringup.placement import placement
from sixdof_msgs.msg import SimObject
from sixdof_msgs.srv import DeleteObject, GetObjectState, SpawnObject

OBJECT = "bench_object"
SHAPES = ("cube", "cylinder", "sphere")
COLOURS = {"cube": (0.9, 0.1, 0.1), "cylinder": (0.1, 0.2, 0.9), "sphere": (0.95, 0.85, 0.1)}


@dataclass
class Trial:
    index: int
    shape: str
    size: float  # the object's width (cube edge, cylinder or sphere diameter), m
    start: tuple[float, float, float]  # x, y, yaw
    target: tuple[float, float]
    height: float = math.nan  # cylinders: drawn separately from the width, m
    outcome: str = "ok"
    detail: str = ""
    error_mm: float = math.nan
    sim_seconds: float = math.nan
    wall_seconds: float = math.nan


@dataclass
class RssTracker:
    """Resident set size of every ROS node, sampled after each trial."""

    samples: dict[str, list[int]] = field(default_factory=dict)  # node -> kB per sample

    @staticmethod
    def node_pids() -> dict[str, int]:
        master = rosgraph.Master("/pick_bench")
        pids = {}
        publishers, subscribers, services = master.getSystemState()
        nodes = {n for entries in (publishers, subscribers, services) for _, names in entries for n in names}
        for node in sorted(nodes):
            try:
                uri = master.lookupNode(node)
                code, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/pick_bench")
            except (OSError, rosgraph.MasterError, xmlrpc.client.Error):
                continue
            if code == 1:
                pids[node] = int(pid)
        return pids

    @staticmethod
    def rss_kb(pid: int) -> int | None:
        try:
            with open(f"/proc/{pid}/status", encoding="ascii") as status:
                for line in status:
                    if line.startswith("VmRSS:"):
                        return int(line.split()[1])
        except OSError:
            return None
        return None

    def sample(self) -> None:
        for node, pid in self.node_pids().items():
            if node.startswith("/pick_bench"):
                continue
            kb = self.rss_kb(pid)
            if kb is not None:
                self.samples.setdefault(node, []).append(kb)

    def write_series(self, path: str) -> None:
        """Every sample as CSV: trial (1-based, in sampling order), node, RSS in kB."""
        with open(path, "w", encoding="utf-8") as out:
            out.write("trial,node,rss_kb\n")
            for node, kb in sorted(self.samples.items()):
                for trial, value in enumerate(kb, 1):
                    out.write(f"{trial},{node},{value}\n")

    def growth_mb(self, warmup: int) -> dict[str, tuple[float, float]]:
        """node -> (RSS at the end of the warm-up, growth since then), MB."""
        result = {}
        for node, kb in self.samples.items():
            if len(kb) > warmup:
                base = kb[warmup - 1] if warmup > 0 else kb[0]
                result[node] = (base / 1024.0, (kb[-1] - base) / 1024.0)
        return result


class Bench:
    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.rng = random.Random(args.seed)
        self.driver = ArmDriver(
            wait_for_servers=args.wait,
            velocity_scaling=args.velocity_scaling,
            acceleration_scaling=args.velocity_scaling,
        )
        sim = args.sim_ns.rstrip("/")
        for service in ("spawn_object", "delete_object", "get_object_state", "reset_world"):
            rospy.wait_for_service(f"{sim}/{service}", timeout=args.wait)
        self.spawn = rospy.ServiceProxy(f"{sim}/spawn_object", SpawnObject)
        self.delete = rospy.ServiceProxy(f"{sim}/delete_object", DeleteObject)
        self.get_state = rospy.ServiceProxy(f"{sim}/get_object_state", GetObjectState)
        self.reset_world = rospy.ServiceProxy(f"{sim}/reset_world", Empty)
        self.recoveries = 0
        self.home = args.home or self.driver.home

    # The random layout -------------------------------------------------------------------------------
    def random_point(self) -> tuple[float, float]:
        xmin, xmax, ymin, ymax = self.args.region
        return self.rng.uniform(xmin, xmax), self.rng.uniform(ymin, ymax)

    def make_trial(self, index: int) -> Trial:
        shape = self.rng.choice(self.args.shapes)
        size = self.rng.uniform(0.03, 0.06)
        x, y = self.random_point()
        yaw = self.rng.uniform(-math.pi, math.pi)
        while True:
            tx, ty = self.random_point()
            if math.dist((x, y), (tx, ty)) >= self.args.min_separation:
                break
        trial = Trial(index, shape, size, (x, y, yaw), (tx, ty))
        if shape == "cylinder":  # last draw of the trial: the sequence is that of every earlier run of the bench
            trial.height = self.rng.uniform(0.03, 0.06)
        return trial

    def sim_object(self, trial: Trial) -> SimObject:
        obj = SimObject(name=OBJECT, mass=0.1, friction=0.8)
        primitive = SolidPrimitive()
        if trial.shape == "cube":
            primitive.type, primitive.dimensions = SolidPrimitive.BOX, [trial.size] * 3
        elif trial.shape == "cylinder":
            primitive.type, primitive.dimensions = SolidPrimitive.CYLINDER, [trial.height, trial.size / 2.0]
        else:
            primitive.type, primitive.dimensions = SolidPrimitive.SPHERE, [trial.size / 2.0]
        obj.shape = primitive
        x, y, yaw = trial.start
        obj.pose = Pose()
        obj.pose.position.x, obj.pose.position.y, obj.pose.position.z = x, y, self.half_height(primitive)
        obj.pose.orientation.z, obj.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
        obj.color = ColorRGBA(*COLOURS[trial.shape], 1.0)
        return obj

    @staticmethod
    def half_height(shape: SolidPrimitive) -> float:
        if shape.type == SolidPrimitive.BOX:
            return shape.dimensions[2] / 2.0
        if shape.type == SolidPrimitive.CYLINDER:
            return shape.dimensions[0] / 2.0
        return shape.dimensions[0]

    # One trial -----------------------------------------------------------------------------------------
    def wait_in_scene(self, present: bool) -> bool:
        deadline = time.monotonic() + self.args.wait
        while time.monotonic() < deadline and not rospy.is_shutdown():
            known = OBJECT in self.driver.scene.get_known_object_names()
            attached = OBJECT in self.driver.scene.get_attached_object_names()
            if (known or attached) == present:
                return True
            time.sleep(0.05)
        return False

    def classify(self) -> str:
        return {UNREACHABLE: "unreachable", GRIPPER: "gripper"}.get(self.driver.last_failure_kind, "planning")

    def held(self) -> bool:
        return bool(self.get_state(OBJECT).attached_to)

    def run_trial(self, trial: Trial) -> Trial:
        driver = self.driver
        obj = self.sim_object(trial)
        response = self.spawn(obj)
        if not response.success:
            raise SixdofCommanderError(f"spawning the bench object failed: {response.status_message}")
        rospy.sleep(0.3)  # settle (simulated time)
        if not self.wait_in_scene(True):
            raise SixdofCommanderError(f"'{OBJECT}' never appeared in the planning scene within {self.args.wait} s")
        sim_start, wall_start = rospy.get_time(), time.monotonic()
        rest_z = self.half_height(obj.shape)
        try:
            if not driver.grasp(OBJECT):
                trial.outcome, trial.detail = self.classify(), driver.last_failure
            elif not driver.lift():
                trial.outcome, trial.detail = self.classify(), driver.last_failure
            elif not self.held():
                trial.outcome, trial.detail = "grasp", "the object was not held after lifting"
            elif not driver.release_at([trial.target[0], trial.target[1], rest_z]):
                lost = not self.held()
                trial.outcome = "slip" if lost else self.classify()
                trial.detail = driver.last_failure
            elif not driver.retreat():
                trial.outcome, trial.detail = self.classify(), driver.last_failure
        except SixdofCommanderError as err:
            trial.outcome, trial.detail = "planning", str(err)
        trial.sim_seconds = rospy.get_time() - sim_start
        trial.wall_seconds = time.monotonic() - wall_start
        if trial.outcome == "ok":
            rospy.sleep(0.5)
            result = placement(self.get_state(OBJECT).object.pose, (trial.target[0], trial.target[1], rest_z))
            trial.error_mm = result.error * 1000.0
            tilt = math.degrees(result.tilt)
            tilted = trial.shape != "sphere" and tilt > self.args.tilt  # a sphere has no upright
            if result.error > self.args.tolerance or tilted:
                trial.outcome = "place"
                trial.detail = f"rests {trial.error_mm:.1f} mm from the target, tilted {tilt:.1f} deg"
        self.reset(trial)
        return trial

    def reset(self, trial: Trial) -> None:
        """Forget the object (planning scene and simulator), open the gripper and go home. When that fails
        (a finger jammed, the arm stuck), the simulator's world is reset and the trial says so."""
        try:
            self.clear()
        except SixdofCommanderError as err:
            trial.detail += f"; cleaning up failed ({err}): world reset"
            if trial.outcome == "ok":
                trial.outcome = "cleanup"
            self.recoveries += 1
            self.reset_world()
            rospy.sleep(0.5)
            self.clear()

    def clear(self) -> None:
        driver = self.driver
        # The object goes first: whatever a failure left between the fingers is then gone.
        self.delete(OBJECT)  # unknown objects are refused: that is fine here
        # A failure may have left the object attached in the planning scene and in the driver's hand.
        if OBJECT in driver.scene.get_attached_object_names():
            driver.arm.detach_object(OBJECT)
        driver.forget_held()
        if not self.wait_in_scene(False):
            raise SixdofCommanderError(f"'{OBJECT}' stayed in the planning scene after it was deleted")
        rospy.sleep(0.2)
        if not driver.gripper_open():
            raise SixdofCommanderError(f"cannot open the gripper after the trial: {driver.last_failure}")
        if not driver.moveto_named(self.home):
            raise SixdofCommanderError(f"cannot return to '{self.home}': {driver.last_failure}")


def median(values: list[float]) -> float:
    return statistics.median(values) if values else math.nan


def percentile(values: list[float], q: float) -> float:
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, math.ceil(q * len(ordered)) - 1))]


def report(
    args: argparse.Namespace, trials: list[Trial], wall: float, rss: RssTracker | None, recoveries: int, robot: str
) -> tuple[str, bool]:
    ok = [t for t in trials if t.outcome == "ok"]
    failures = Counter(t.outcome for t in trials if t.outcome != "ok")
    rate = 100.0 * len(ok) / len(trials) if trials else 0.0
    title = ("soak" if args.rss else "pick") + (f", {args.label}" if args.label else "")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    lines = [
        f"## {title} (scripts/bench_pick.sh)",
        "",
        f"Run {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} at commit {commit or 'unknown'}, robot '{robot}'"
        + (f" (package {args.label})." if args.label else "."),
        f"{len(trials)} randomized pick-and-place trials, seed {args.seed}"
        + (f" (only trials {', '.join(map(str, args.only))} of the sequence)" if args.only else "")
        + ", headless (simulator as fast as possible),",
        f"velocity scaling {args.velocity_scaling:g}; objects: cube, upright cylinder, sphere, 3-6 cm wide, random",
        "position and yaw in x [{:g}, {:g}] m, y [{:g}, {:g}] m;".format(*args.region),
        f"success = resting within {args.tolerance * 1000:.0f} mm of the target and (cubes and cylinders) "
        f"{args.tilt:g} deg of upright.",
        "",
        "| measure | value |",
        "|---|---|",
        f"| success | {len(ok)}/{len(trials)} ({rate:.1f} %) |",
    ]
    for shape in SHAPES:
        of_shape = [t for t in trials if t.shape == shape]
        if of_shape:
            good = sum(t.outcome == "ok" for t in of_shape)
            lines.append(f"| success, {shape} | {good}/{len(of_shape)} |")
    for kind in ("planning", "unreachable", "gripper", "grasp", "slip", "place", "cleanup"):
        lines.append(f"| failures: {kind} | {failures.get(kind, 0)} |")
    lines.append(f"| world resets to recover (gripper or arm stuck after a trial) | {recoveries} |")
    errors = [t.error_mm for t in ok]
    cycle_sim = [t.sim_seconds for t in trials if t.outcome == "ok"]
    cycle_wall = [t.wall_seconds for t in trials if t.outcome == "ok"]
    lines += [
        f"| place error, median / p95 (successes) | {median(errors):.1f} / {percentile(errors, 0.95):.1f} mm |",
        f"| cycle time, median (simulated) | {median(cycle_sim):.1f} s |",
        f"| cycle time, median (wall) | {median(cycle_wall):.1f} s |",
        f"| wall time of the run | {wall / 60.0:.1f} min |",
    ]
    passed = True
    if rss is not None:
        growth = rss.growth_mb(args.warmup)
        worst = max(growth.items(), key=lambda item: item[1][1], default=None)
        lines.append(f"| nodes sampled (RSS after each trial) | {len(growth)} |")
        if worst is not None:
            lines.append(
                f"| largest RSS growth after {args.warmup} warm-up trials | {worst[1][1]:+.1f} MB ({worst[0]}) |"
            )
        lines += ["", "| node | RSS after warm-up | growth to the end |", "|---|---|---|"]
        for node, (base, grew) in sorted(growth.items()):
            lines.append(f"| {node} | {base:.1f} MB | {grew:+.1f} MB |")
        passed = all(grew <= args.max_growth_mb for _, grew in growth.values()) and len(ok) == len(trials)
    failed = [t for t in trials if t.outcome != "ok"]
    if failed:
        lines += ["", "Failures:", ""]
        for t in failed:
            lines.append(
                f"- trial {t.index} ({t.shape} {t.size * 100:.1f} cm"
                + (f", {t.height * 100:.1f} cm high" if t.shape == "cylinder" else "")
                + f" at ({t.start[0]:.3f}, {t.start[1]:.3f}) -> "
                f"({t.target[0]:.3f}, {t.target[1]:.3f})): {t.outcome}: {t.detail}"
            )
    return "\n".join(lines) + "\n", passed


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--trials", type=int, help="number of trials (default: 100)")
    parser.add_argument("--seed", type=int, default=1, help="random seed (default: 1)")
    parser.add_argument(
        "--only",
        nargs="+",
        type=int,
        metavar="N",
        help="run only these trials (1-based) of the seeded sequence, e.g. to replay a failure; --trials then "
        "defaults to the largest",
    )
    parser.add_argument(
        "--region",
        nargs=4,
        type=float,
        default=[0.28, 0.50, -0.25, 0.25],
        metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
        help="table area (planning frame, m) where objects and targets are drawn (default: 0.28 0.50 -0.25 0.25)",
    )
    parser.add_argument(
        "--shapes", nargs="+", choices=SHAPES, default=list(SHAPES), help="object shapes drawn (default: all)"
    )
    parser.add_argument("--min-separation", type=float, default=0.10, help="start to target, at least (m)")
    parser.add_argument("--tolerance", type=float, default=0.01, help="allowed place error (m, default: 0.01)")
    parser.add_argument(
        "--tilt", type=float, default=10.0, help="allowed tilt of a cube or cylinder from upright (deg, default: 10)"
    )
    parser.add_argument("--home", help="named state each trial returns to (default: the arm group's first SRDF state)")
    parser.add_argument("--velocity-scaling", type=float, default=0.5, help="max velocity scaling in (0, 1]")
    parser.add_argument("--sim-ns", default="sixdof_sim", help="namespace of the simulator's services")
    parser.add_argument("--wait", type=float, default=30.0, help="wall seconds to wait for servers and the scene")
    parser.add_argument("--rss", action="store_true", help="sample every node's RSS after each trial (soak)")
    parser.add_argument("--warmup", type=int, default=20, help="trials before the RSS baseline (default: 20)")
    parser.add_argument("--max-growth-mb", type=float, default=5.0, help="allowed RSS growth per node (MB)")
    parser.add_argument("--rss-series", help="with --rss, write every sample here (CSV: trial, node, rss_kb)")
    parser.add_argument("--report", help="write the markdown report here too")
    parser.add_argument(
        "--label", default="", help="the robot's config package, named in the report's title (scripts/bench_pick.sh)"
    )
    args = parser.parse_args(argv)
    if args.only is not None:
        if any(n < 1 for n in args.only):
            parser.error(f"--only takes trial numbers >= 1, got {args.only}")
        if args.trials is None:
            args.trials = max(args.only)
        elif max(args.only) > args.trials:
            parser.error(f"--only {max(args.only)} is beyond --trials {args.trials}")
    if args.trials is None:
        args.trials = 100
    if args.trials < 1:
        parser.error(f"--trials must be >= 1, got {args.trials}")
    xmin, xmax, ymin, ymax = args.region
    if not (xmin < xmax and ymin < ymax) or not all(math.isfinite(v) for v in args.region):
        parser.error(f"--region must be XMIN < XMAX, YMIN < YMAX, got {args.region}")
    for name in ("min_separation", "tolerance", "tilt", "wait", "max_growth_mb"):
        value = getattr(args, name)
        if not math.isfinite(value) or value <= 0.0:
            parser.error(f"--{name.replace('_', '-')} must be > 0, got {value}")
    if math.hypot(xmax - xmin, ymax - ymin) < args.min_separation:
        parser.error("--region is smaller than --min-separation: no target can be drawn")
    if args.rss_series and not args.rss:
        parser.error("--rss-series needs --rss")
    if args.rss and not 0 <= args.warmup < args.trials:
        parser.error(f"--warmup must be in [0, --trials), got {args.warmup}")
    return args


def main() -> int:
    args = parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("pick_bench", anonymous=True)
    try:
        bench = Bench(args)
        if not bench.driver.moveto_named(bench.home):
            print(f"error: cannot reach '{bench.home}': {bench.driver.last_failure}", file=sys.stderr)
            return 2
        rss = RssTracker() if args.rss else None
        trials: list[Trial] = []
        start = time.monotonic()
        for i in range(args.trials):
            if rospy.is_shutdown():
                break
            trial = bench.make_trial(i + 1)
            if args.only and trial.index not in args.only:
                continue  # drawn all the same: trial N is the same object and target as in a full run
            print(
                f"trial {trial.index}/{args.trials}: {trial.shape} {trial.size * 100:.1f} cm at "
                f"({trial.start[0]:.3f}, {trial.start[1]:.3f}, yaw {math.degrees(trial.start[2]):.0f} deg) -> "
                f"({trial.target[0]:.3f}, {trial.target[1]:.3f})",
                flush=True,
            )
            bench.run_trial(trial)
            trials.append(trial)
            if rss is not None:
                rss.sample()
            print(
                f"  -> {trial.outcome}"
                + (f" ({trial.error_mm:.1f} mm)" if trial.outcome == "ok" else f": {trial.detail}")
                + f"  [{trial.wall_seconds:.1f} s wall]",
                flush=True,
            )
        robot = bench.driver.arm.robot_description.name
        text, passed = report(args, trials, time.monotonic() - start, rss, bench.recoveries, robot)
        if rss is not None and args.rss_series:
            rss.write_series(args.rss_series)
    except (SixdofCommanderError, rospy.ROSException, rospy.ServiceException) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print()
    print(text)
    if args.report:
        with open(args.report, "w", encoding="utf-8") as out:
            out.write(text)
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
