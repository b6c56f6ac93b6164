#!/usr/bin/env python3
"""The operator host's side of test/ros/multihost.py: a moveit_commander script run in the second network
namespace. It moves the arm group's first joint by 1 rad at 10 % speed (a motion of several seconds), prints
"MOVING" as the goal goes out and one JSON line with go()'s outcome when it returns; then it waits for a line on
stdin (the test restores the link) and moves back, printing a second JSON line. No robot names are assumed: the
group is the SRDF's group with the most active joints."""

import json
import sys
import time

import moveit_commander
import rospy


def outcome(arm: moveit_commander.MoveGroupCommander, ok: bool, started: float) -> str:
    code = arm.last_error
    return json.dumps(
        {"ok": bool(ok), "code": code.val, "message": code.message, "seconds": time.monotonic() - started}
    )


def main() -> int:
    moveit_commander.roscpp_initialize(sys.argv)
    rospy.init_node("multihost_client", anonymous=True, disable_signals=True)
    deadline = time.monotonic() + 180.0
    while True:  # the robot host may still be starting: move_group serves the robot model
        try:
            robot = moveit_commander.RobotCommander()
            break
        except moveit_commander.MoveItCommanderException:
            if time.monotonic() > deadline:
                raise
            time.sleep(1.0)
    groups = robot.get_group_names()
    group = max(groups, key=lambda g: len(robot.get_active_joint_names(g)))
    arm = moveit_commander.MoveGroupCommander(group, wait_for_servers=60.0)
    arm.set_max_velocity_scaling_factor(0.1)
    arm.set_max_acceleration_scaling_factor(0.1)
    start = arm.get_current_joint_values()
    joint = arm.get_active_joints()[0]
    lower, upper = robot.get_joint(joint).bounds()
    target = list(start)
    target[0] = start[0] + 1.0 if start[0] + 1.0 <= upper else start[0] - 1.0
    if not lower <= target[0] <= upper:
        print(json.dumps({"error": f"joint {joint} cannot move 1 rad inside [{lower}, {upper}]"}), flush=True)
        return 2
    print("MOVING", flush=True)
    started = time.monotonic()
    ok = arm.go(target, wait=True)
    print(outcome(arm, ok, started), flush=True)
    sys.stdin.readline()  # the link is back
    started = time.monotonic()
    ok = arm.go(start, wait=True)
    print(outcome(arm, ok, started), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
