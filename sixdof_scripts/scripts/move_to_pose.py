#!/usr/bin/env python3
"""Plan and move the arm's tip link to x y z (metres) roll pitch yaw (degrees, fixed axes) in the base frame.

rosrun sixdof_scripts move_to_pose.py 0.366 0 0.286 -180 0.688 179.995
"""

import argparse
import sys

import rospy
from sixdof_commander import MoveGroup, SixdofCommanderError, rad
from sixdof_commander.cli import add_group_arguments, report_motion, scale


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("values", nargs=6, type=float, metavar="X Y Z ROLL PITCH YAW")
    add_group_arguments(parser)
    parser.add_argument("--plan-only", action="store_true", help="plan, do not move")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("move_to_pose", anonymous=True)
    try:
        group = MoveGroup(args.group, ns=args.ns)
        scale(group, args)
        group.set_pose_target(args.values[:3] + rad(args.values[3:]))
        if args.plan_only:
            ok, trajectory, planning_time, code = group.plan()
            points = len(trajectory.joint_trajectory.points)
            print(
                f"plan: {'ok' if ok else 'FAILED'} in {planning_time:.3f} s, {points} points ({group.last_error})"
            )
            return 0 if ok else 1
        return report_motion(str(args.values), group.go(wait=True), group)
    except SixdofCommanderError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
