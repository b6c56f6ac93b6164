#!/usr/bin/env python3
"""Pick a named object of the simulated world and place it at (x, y) on the table, through the paper's
stages (home, pick pose, after pick pose, place pose, after place pose) with top-down grasps computed from
the object's pose and the gripper's grasping information (the config package's, from move_group). Every
repetition is verified: the object must rest within --tolerance of the target. Odd repetitions carry the
object to --place, even ones back to where it started. The arm group, the gripper and the home state are the
package's; nothing here names a robot.

    rosrun sixdof_scripts pick_place.py --object red_cube --place 0.40 0.20 --repetitions 2

Exit codes: 0 every repetition placed the object, 1 a stage failed (an object the robot cannot grasp from the
top at its spot, or place at the target, is "unreachable"), 2 bad arguments or a missing node or object.
"""

import argparse
import math
import sys
import time
from collections.abc import Callable

import rospy
from sixdof_commander import ArmDriver, SixdofCommanderError


def timed(label: str, action: Callable[[], bool]) -> bool:
    """Run one stage, printing its name, outcome and duration."""
    print(f"  {label:<17s} ", end="", flush=True)
    start = time.monotonic()
    ok = bool(action())
    print(f"{'ok' if ok else 'FAILED'}  ({time.monotonic() - start:5.1f} s)", flush=True)
    return ok


def object_position(driver: ArmDriver, name: str) -> tuple[float, float, float]:
    p = driver.get_object_state(name).object.pose.position
    return (p.x, p.y, p.z)


def pick_and_place(driver: ArmDriver, name: str, target: tuple[float, float], rest_z: float, home: str) -> bool:
    """One pick-and-place cycle through the paper's stages."""
    stages = [
        (home, lambda: driver.moveto_named(home)),
        ("pick pose", lambda: driver.grasp(name)),
        ("after pick pose", driver.lift),
        ("place pose", lambda: driver.release_at([target[0], target[1], rest_z])),
        ("after place pose", driver.retreat),
    ]
    for label, action in stages:
        if not timed(label, action):
            print(f"  failure ({driver.last_failure_kind}): {driver.last_failure}", file=sys.stderr)
            return False
    return True


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--object", default="red_cube", help="simulator object to move (default: red_cube)")
    parser.add_argument(
        "--place",
        nargs=2,
        type=float,
        default=[0.40, 0.20],
        metavar=("X", "Y"),
        help="place location on the table, metres (default: 0.40 0.20)",
    )
    parser.add_argument("--repetitions", type=int, default=1, help="pick-and-place cycles (default: 1)")
    parser.add_argument("--tolerance", type=float, default=0.01, help="allowed final error, metres (default: 0.01)")
    parser.add_argument(
        "--home", help="named state of the arm to start each cycle from (default: the arm group's first SRDF state)"
    )
    parser.add_argument("--velocity-scaling", type=float, default=0.5, help="max velocity scaling in (0, 1]")
    parser.add_argument("--ns", default="", help="namespace of the planner and simulator nodes")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    if args.repetitions < 1:
        parser.error(f"--repetitions must be >= 1, got {args.repetitions}")
    if not math.isfinite(args.tolerance) or args.tolerance <= 0.0:
        parser.error(f"--tolerance must be > 0, got {args.tolerance}")

    rospy.init_node("pick_place", anonymous=True)
    try:
        driver = ArmDriver(
            ns=args.ns, velocity_scaling=args.velocity_scaling, acceleration_scaling=args.velocity_scaling
        )
        home = args.home or driver.home
        start = object_position(driver, args.object)
        targets = [tuple(args.place), start[:2]]
        succeeded = 0
        total_start = time.monotonic()
        for i in range(args.repetitions):
            target = targets[i % 2]
            print(f"repetition {i + 1}/{args.repetitions}: '{args.object}' -> ({target[0]:.3f}, {target[1]:.3f})")
            cycle_start = time.monotonic()
            if not pick_and_place(driver, args.object, target, start[2], home):
                break
            # Let the released object settle before measuring where it rests.
            rospy.sleep(0.5)
            x, y, z = object_position(driver, args.object)
            error = math.dist((x, y, z), (target[0], target[1], start[2]))
            verdict = "ok" if error <= args.tolerance else "FAILED"
            print(
                f"  result: object at ({x:.3f}, {y:.3f}, {z:.3f}), error {error * 1000:.1f} mm "
                f"(limit {args.tolerance * 1000:.0f} mm): {verdict}; cycle {time.monotonic() - cycle_start:.1f} s"
            )
            if error > args.tolerance:
                break
            succeeded += 1
        if succeeded == args.repetitions:
            timed(home, lambda: driver.moveto_named(home))
        print(
            f"{succeeded}/{args.repetitions} pick-and-place cycles succeeded in {time.monotonic() - total_start:.1f} s"
        )
        return 0 if succeeded == args.repetitions else 1
    except SixdofCommanderError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
