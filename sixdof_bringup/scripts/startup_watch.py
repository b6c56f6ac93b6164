#!/usr/bin/env python3
"""Ends the launch when the simulator cannot start: simulation.launch.xml runs this node `required`, and it exits
(ending every node of the launch) when the simulator died before its first /clock message, with the simulator's
own one-line error (its `~startup_error` parameter, which it sets before it exits) or, if it died without one (a
signal), the exit as far as it can be seen. Once /clock has come, it only idles: a later crash of the simulator
leaves the launch as it is (with `sim_respawn` the simulator comes back, without it move_group keeps running).

Without it, move_group and scene_mirror of a stack whose simulator refused its URDF or world would wait forever
for a clock. Parameter `~node`: the simulator node's name (default `sixdof_sim`, resolved in this namespace).
"""

from __future__ import annotations

import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
from rosgraph_msgs.msg import Clock

POLL = 0.05  # s of wall time between looks at the simulator


def simulator_pid(master: rosgraph.Master, node: str) -> int | None:
    """The pid of the live process registered as `node`, None while there is none (not started yet, or gone)."""
    try:
        code, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(node)).getPid(rospy.get_name())
    except (OSError, rosgraph.MasterError, xmlrpc.client.Error):
        return None
    return int(pid) if code == 1 else None


def startup_error(node: str) -> str:
    error = rospy.get_param(f"{node}/startup_error", "")
    return error if isinstance(error, str) else ""


def watch(node: str) -> str:
    """Until the simulator's first /clock ("") or its death before it (the reason)."""
    ticked = threading.Event()
    subscriber = rospy.Subscriber("/clock", Clock, lambda _msg: ticked.set(), queue_size=1)
    master = rosgraph.Master(rospy.get_name())
    seen = False
    try:
        # Wall clock throughout: with use_sim_time, ROS time stands still until the first /clock.
        while not rospy.is_shutdown():
            if ticked.is_set():
                return ""
            error = startup_error(node)
            if error:
                return error
            alive = simulator_pid(master, node) is not None
            if seen and not alive and not ticked.is_set():
                time.sleep(0.5)  # an error it set while exiting reaches the parameter server first
                return startup_error(node) or "it exited (see its output above)"
            seen = seen or alive
            time.sleep(POLL)
        return ""
    finally:
        subscriber.unregister()


def main() -> int:
    rospy.init_node("startup_watch", disable_signals=False)
    node = rospy.resolve_name(rospy.get_param("~node", "sixdof_sim"))
    reason = watch(node)
    if rospy.is_shutdown():
        return 0
    if reason:
        # One line, the last the launch prints before it shuts down.
        print(f"[startup_watch] {node} could not start: {reason}", file=sys.stderr, flush=True)
        return 1
    rospy.loginfo("%s is up (first /clock): watching ends", node)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
