#!/usr/bin/env python3
"""Plan and move a planning group to one of its named states (SRDF group states).

rosrun sixdof_scripts move_to_named.py "home pose"
rosrun sixdof_scripts move_to_named.py --list
"""

import argparse
import sys

import rospy
from sixdof_commander import MoveGroup, SixdofCommanderError
from sixdof_commander.cli import add_group_arguments, report_motion, scale


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("name", nargs="?", help="named state, e.g. 'home pose'")
    add_group_arguments(parser)
    parser.add_argument("--list", action="store_true", help="print the group's named states and exit")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    if not args.list and args.name is None:
        parser.error("give a named state or --list")
    rospy.init_node("move_to_named", anonymous=True)
    try:
        group = MoveGroup(args.group, ns=args.ns)
        if args.list:
            for name in group.get_named_targets():
                values = ", ".join(f"{j}={v:.4f}" for j, v in group.get_named_target_values(name).items())
                print(f"{name}: {values}")
            return 0
        scale(group, args)
        group.set_named_target(args.name)
        return report_motion(f"'{args.name}'", group.go(wait=True), group)
    except SixdofCommanderError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
