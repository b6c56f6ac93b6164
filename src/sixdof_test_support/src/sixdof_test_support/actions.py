"""Waiting on actionlib goals in tests."""

from __future__ import annotations

import time

import actionlib
import rospy
from actionlib import CommState


def wait_for_goal(client: actionlib.SimpleActionClient, timeout: float) -> bool:
    """Whether the client's last goal finished within `timeout` wall-clock seconds.

    Waits on the goal handle's comm state, not SimpleActionClient.wait_for_result (ros/actionlib#206): a result
    that arrives before send_goal has stored the new handle (a goal the server rejects or finishes at once) is
    dropped by the simple client's transition callback ("a goal handle that we're not tracking"), so its simple
    state never becomes DONE, while the handle itself sees the result; get_state() and get_result() read the
    handle. The wall clock, not ROS time: simulated time stands still while the simulator is paused, stopped or
    dead, so a timeout counted in it could wait forever.
    """
    deadline = time.monotonic() + timeout
    while client.gh is None or client.gh.get_comm_state() != CommState.DONE:
        if time.monotonic() >= deadline or rospy.is_shutdown():
            return False
        time.sleep(0.005)
    return True
