"""Helpers of the fault and fuzz rostests: nodes' pids from the master, and calls bounded on the wall clock.

Simulated time stands still while the simulator is stopped or dead, so everything here waits on the wall clock
(rospy's and actionlib's timeouts count ROS time and would wait forever)."""

from __future__ import annotations

import concurrent.futures
import os
import signal
import time
import xmlrpc.client

import actionlib
import rosgraph
import rosnode
import rospy
from e2e import wait_for_action_server, wait_for_stack
from moveit_msgs.msg import ExecuteTrajectoryAction
from moveit_msgs.srv import GetMotionPlan
from sixdof_commander import MoveGroup

_POOL = concurrent.futures.ThreadPoolExecutor(max_workers=4)


def node_pid(name: str) -> int:
    """The pid of a running node (its getPid over XML-RPC); raises when the master does not know it."""
    uri = rosnode.get_api_uri(rosgraph.Master("/faults"), name, skip_cache=True)
    if not uri:
        raise LookupError(f"node '{name}' is not registered")
    code, message, pid = xmlrpc.client.ServerProxy(uri).getPid("/faults")
    if code != 1:
        raise LookupError(f"getPid of '{name}': {message}")
    return int(pid)


def signal_node(name: str, sig: signal.Signals) -> int:
    """Sends sig to the node's process; returns its pid."""
    pid = node_pid(name)
    os.kill(pid, sig)
    return pid


def wait_until(predicate, timeout: float, what: str, period: float = 0.05):
    """Polls predicate until it returns a true value (returned) for at most timeout wall seconds."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            value = predicate()
        except Exception:  # noqa: BLE001 - e.g. a node not registered yet: keep polling
            value = None
        if value:
            return value
        time.sleep(period)
    raise AssertionError(f"{what}: not within {timeout} s")


def bounded_call(function, *args, timeout: float, what: str):
    """function(*args) in a worker thread; AssertionError when it does not return within timeout wall seconds
    (the hang is the failure: the thread is left behind)."""
    future = _POOL.submit(function, *args)
    try:
        return future.result(timeout=timeout)
    except concurrent.futures.TimeoutError:
        raise AssertionError(f"{what} did not return within {timeout} s") from None


def connect(node: str, group: str) -> tuple[MoveGroup, rospy.ServiceProxy, actionlib.SimpleActionClient]:
    """Starts the test node, waits for the stack and returns the group's commander, the plan_kinematic_path
    service and an execute_trajectory client."""
    rospy.init_node(node)
    wait_for_stack()
    execute = actionlib.SimpleActionClient("execute_trajectory", ExecuteTrajectoryAction)
    wait_for_action_server(execute, 60.0, "execute_trajectory")
    return MoveGroup(group, wait_for_servers=60.0), rospy.ServiceProxy("plan_kinematic_path", GetMotionPlan), execute
