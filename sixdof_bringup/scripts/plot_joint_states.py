#!/usr/bin/env python3
"""Plots the joint trajectories recorded in a bag (topic /joint_states by default) into a PNG.

rosrun sixdof_bringup plot_joint_states.py demo.bag joints.png [--topic /joint_states]
"""

import argparse
import sys

import rosbag

from sixdof_bringup.plots import plot_joint_series, series_from_messages


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bag", help="bag file holding sensor_msgs/JointState messages")
    parser.add_argument("output", help="PNG file to write")
    parser.add_argument("--topic", default="/joint_states", help="joint state topic (default: /joint_states)")
    parser.add_argument("--title", default="sixdof pick and place: joint trajectories", help="plot title")
    args = parser.parse_args()
    with rosbag.Bag(args.bag) as bag:
        samples = [
            (msg.header.stamp.to_sec(), msg.name, msg.position) for _, msg, _ in bag.read_messages(topics=[args.topic])
        ]
    try:
        series = series_from_messages(samples)
    except ValueError as err:
        print(f"error: {args.bag}: {err}", file=sys.stderr)
        return 1
    plot_joint_series(series, args.output, args.title)
    print(f"{len(series.times)} samples of {len(series.names)} joints over {series.times[-1]:.1f} s -> {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
