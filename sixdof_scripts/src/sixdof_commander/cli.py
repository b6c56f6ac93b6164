"""What the rosrun motion scripts (move_to_pose.py, move_to_named.py) share: the planning group's options, the
group they name and the one-line report of a motion."""

import argparse

from .move_group import MoveGroup


def add_group_arguments(parser: argparse.ArgumentParser) -> None:
    """--group, --ns and --velocity-scaling (also the acceleration scaling)."""
    parser.add_argument("--group", default="arm", help="planning group (default: arm)")
    parser.add_argument("--ns", default="", help="namespace of the move_group node")
    parser.add_argument("--velocity-scaling", type=float, default=0.5, help="max velocity scaling in (0, 1]")


def scale(group: MoveGroup, args: argparse.Namespace) -> None:
    """Applies --velocity-scaling to the group's velocities and accelerations."""
    group.set_max_velocity_scaling_factor(args.velocity_scaling)
    group.set_max_acceleration_scaling_factor(args.velocity_scaling)


def report_motion(target: str, ok: bool, group: MoveGroup) -> int:
    """Prints 'move to <target>: ok' or the group's last error; the script's exit code (0 or 1)."""
    print(f"move to {target}: {'ok' if ok else f'FAILED: {group.last_error}'}")
    return 0 if ok else 1
