"""Shared helpers of the end-to-end rostests: waiting for the stack, settled joint states, tf poses."""

from __future__ import annotations

import contextlib
import math
import time
import unittest

import numpy as np
import rospy
import tf2_ros
from moveit_msgs.msg import PlanningSceneComponents
from moveit_msgs.srv import GetPlanningScene, GetPlanningSceneRequest
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import JointState

from sixdof_msgs.srv import GetObjectState

# Hang guard only (the tests assert results, never durations): the stack is up in seconds when healthy.
STARTUP_TIMEOUT = 240.0



@contextlib.contextmanager
def case(**labels):
    """Names a case inside a test: an assertion failing inside it is re-raised with the labels in its message.
    (unittest's subTest is not used: rosunit's XML output counts failed subTests but drops which and why.)"""
    try:
        yield
    except AssertionError as exc:
        label = ", ".join(f"{k}={v}" for k, v in labels.items())
        raise AssertionError(f"[{label}] {exc}") from None

def wait_for_stack(object_name: str = "red_cube") -> None:
    """Until move_group answers and the scene mirror has put object_name into the planning scene."""
    rospy.wait_for_service("get_planning_scene", timeout=STARTUP_TIMEOUT)
    rospy.wait_for_service("sixdof_sim/get_object_state", timeout=STARTUP_TIMEOUT)
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while time.monotonic() < deadline:
        names = planning_scene(PlanningSceneComponents.WORLD_OBJECT_NAMES).world.collision_objects
        if object_name in [o.id for o in names]:
            return
        time.sleep(0.1)
    raise AssertionError(f"'{object_name}' never appeared in the planning scene")


def wait_for_action_server(client, timeout: float, what: str) -> None:
    """Until an actionlib client's server is up; AssertionError naming `what` after `timeout` wall-clock seconds
    (a free-running simulator's clock would spend a simulated timeout in a fraction of that)."""
    deadline = time.monotonic() + timeout
    while not client.wait_for_server(rospy.Duration(0.05)):
        if time.monotonic() > deadline or rospy.is_shutdown():
            raise AssertionError(f"no {what} action server within {timeout} s")


# The world objects (poses and shapes) and the attached objects.
OBJECTS = PlanningSceneComponents.WORLD_OBJECT_GEOMETRY | PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS


def planning_scene(components: int = OBJECTS):
    """These parts (PlanningSceneComponents flags) of move_group's planning scene."""
    request = GetPlanningSceneRequest()
    request.components.components = components
    return rospy.ServiceProxy("get_planning_scene", GetPlanningScene)(request).scene


def object_state(name: str):
    response = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)(name)
    assert response.success, response.status_message
    return response


# The default world's collision objects (sixdof_sim worlds/default.yaml), which scene_mirror puts into the scene.
MIRRORED_OBJECTS = ("table", "red_cube", "blue_cylinder", "yellow_sphere", "green_block")


def assert_scene_mirrors_simulator(test: unittest.TestCase, support_clearance: float) -> tuple[dict, dict]:
    """Each of MIRRORED_OBJECTS is in the planning scene within 2 mm of the simulator's pose (the mirror sends MOVE
    only for changes above 1 mm; static objects, the table the robot stands on, support_clearance lower), and the
    visual-only place_marker is not. Returns the scene's objects and the simulator's states, by name."""
    world = {o.id: o for o in planning_scene().world.collision_objects}
    states = {}
    for name in MIRRORED_OBJECTS:
        with case(object=name):
            test.assertIn(name, world)
            sim = states[name] = object_state(name).object
            drop = support_clearance if sim.is_static else 0.0
            expected = (sim.pose.position.x, sim.pose.position.y, sim.pose.position.z - drop)
            mirrored = world[name].pose.position
            test.assertLess(math.dist(expected, (mirrored.x, mirrored.y, mirrored.z)), 0.002)
    test.assertNotIn("place_marker", world, "a visual-only marker is not an obstacle")
    return world, states


def settled_joint_state(velocity_limit: float = 1e-3, sim_timeout: float = 5.0) -> JointState:
    """The first joint state whose joint speeds are all below velocity_limit (rad/s, m/s), or the last one
    after sim_timeout simulated seconds: the servos keep converging after a controller reports success."""
    end = rospy.get_time() + sim_timeout
    while True:
        msg = rospy.wait_for_message("joint_states", JointState, timeout=30.0)
        if all(abs(v) < velocity_limit for v in msg.velocity) or rospy.get_time() >= end:
            return msg


def object_at_rest(name: str, speed: float = 1e-3, sim_timeout: float = 5.0):
    """The simulator's state of object `name` once its linear (m/s) and angular (rad/s) speeds are below `speed`,
    or the last one after sim_timeout simulated seconds (the caller asserts where it lies)."""
    end = rospy.get_time() + sim_timeout
    while True:
        state = object_state(name)
        v, w = state.twist.linear, state.twist.angular
        if max(math.hypot(v.x, v.y, v.z), math.hypot(w.x, w.y, w.z)) < speed or rospy.get_time() >= end:
            return state
        rospy.rostime.wallsleep(0.01)


class TfPoses:
    """Poses of robot links in the base frame, from tf (robot_state_publisher of the simulator's joints)."""

    def __init__(self) -> None:
        self.buffer = tf2_ros.Buffer(cache_time=rospy.Duration(30.0))
        self.listener = tf2_ros.TransformListener(self.buffer)

    def pose(self, link: str, stamp: rospy.Time, frame: str = "base_link") -> tuple[np.ndarray, Rotation]:
        """(position, rotation) of link in frame for a robot at rest since stamp (e.g. a settled joint
        state's): the newest published tf sample at or after stamp (waits for one). Not tf's value *at* stamp:
        robot_state_publisher reads joint_states with a queue of one, so on a loaded machine its samples can lie
        far apart and tf would interpolate between a sample taken during the motion and one after it."""
        # The lookup at stamp succeeds only once a sample at or after stamp has arrived.
        self.buffer.lookup_transform(frame, link, stamp, rospy.Duration(30.0))
        latest = self.buffer.lookup_transform(frame, link, rospy.Time(0))
        assert latest.header.stamp >= stamp, f"newest tf sample of '{link}' predates {stamp.to_sec()}"
        t = latest.transform
        position = np.array([t.translation.x, t.translation.y, t.translation.z])
        r = t.rotation
        return position, Rotation.from_quat([r.x, r.y, r.z, r.w])
