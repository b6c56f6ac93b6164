#!/usr/bin/env python3
"""Checks that a simulator object rests upright at a place on the table: exit 0 if its centre is within
--tolerance of (x, y, z) and it is tilted less than --max-tilt degrees; 1 otherwise.
z defaults to the centre height of the object resting upright on z = 0 (from its shape).

    rosrun sixdof_bringup object_at.py red_cube 0.40 0.20 [--z 0.02] [--tolerance 0.01]
"""

import argparse
import math
import sys

import rospy
from shape_msgs.msg import SolidPrimitive

from sixdof_bringup.placement import placement
from sixdof_msgs.srv import GetObjectState


def resting_height(shape: SolidPrimitive) -> float:
    """Height of an upright primitive's centre above the surface it rests on."""
    if shape.type == SolidPrimitive.BOX:
        return shape.dimensions[2] / 2.0
    if shape.type == SolidPrimitive.SPHERE:
        return shape.dimensions[0]
    if shape.type == SolidPrimitive.CYLINDER:
        return shape.dimensions[0] / 2.0
    raise ValueError(f"no resting height for shape type {shape.type}: give --z")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("object", help="simulator object name")
    parser.add_argument("x", type=float, help="target x (m)")
    parser.add_argument("y", type=float, help="target y (m)")
    parser.add_argument("--z", type=float, default=None, help="target z of the centre (m); default: resting on z=0")
    parser.add_argument("--tolerance", type=float, default=0.01, help="allowed position error (m, default 0.01)")
    parser.add_argument("--max-tilt", type=float, default=5.0, help="allowed tilt from upright (deg, default 5)")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("object_at", anonymous=True)
    rospy.wait_for_service("sixdof_sim/get_object_state", timeout=30.0)
    state = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)(args.object)
    if not state.success:
        print(f"error: object '{args.object}': {state.status_message}", file=sys.stderr)
        return 1
    z = args.z if args.z is not None else resting_height(state.object.shape)
    result = placement(state.object.pose, (args.x, args.y, z))
    p = state.object.pose.position
    ok = result.error <= args.tolerance and math.degrees(result.tilt) <= args.max_tilt and not state.attached_to
    held = f", held by '{state.attached_to}'" if state.attached_to else ""
    print(
        f"'{args.object}' at ({p.x:.4f}, {p.y:.4f}, {p.z:.4f}), target ({args.x:.4f}, {args.y:.4f}, {z:.4f}): "
        f"error {result.error * 1000:.1f} mm (limit {args.tolerance * 1000:.0f}), "
        f"tilt {math.degrees(result.tilt):.2f} deg (limit {args.max_tilt:g}){held} -> {'ok' if ok else 'FAILED'}"
    )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
