#!/usr/bin/env python3
"""rostest: the simulator node's conveyor and suction interfaces. The ~world parameter describes the belt, its object,
source and sink; set_conveyor changes a belt's speed and names bad input; conveyor_states counts the source's spawns
and the sink's deletions; the vacuum on gripper_cmd holds an object
under the cup (a grasp event and attached_to as the grasp fix gives) and lets it go."""

import math
import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import GripperCommandAction, GripperCommandGoal
from geometry_msgs.msg import Pose
from shape_msgs.msg import SolidPrimitive
from sim_test_util import sim_service, wait_for_servers

from sixdof_msgs.msg import ConveyorStates, GraspEvent, ObjectStates, SimObject
from sixdof_msgs.srv import SetConveyor, SpawnObject
from sixdof_test_support.actions import wait_for_goal

# Outcome bounds (wall-clock seconds): the simulator runs free, each step is cheap.
TIMEOUT = 60.0


def wait_for(condition, what: str, topic: str, msg_type: type):
    """The first message on `topic` for which condition(msg) holds, within TIMEOUT wall-clock seconds."""
    deadline = time.monotonic() + TIMEOUT
    while not rospy.is_shutdown() and time.monotonic() < deadline:
        msg = rospy.wait_for_message(topic, msg_type, TIMEOUT)
        if condition(msg):
            return msg
    raise AssertionError(f"no {what} on {topic}")


class SimConveyor(unittest.TestCase):
    def test_world_parameter_describes_the_belt(self):
        world = rospy.get_param("sixdof_sim/world")
        self.assertEqual(world["name"], "conveyor_test")
        (belt,) = world["conveyors"]
        (belt_object,) = (o for o in world["objects"] if o["conveyor"] == "belt")
        self.assertEqual((belt["name"], belt_object["name"]), ("belt", "belt"))
        for entry in (belt, belt_object):
            for key, expected in (("position", [1.0, 0.0, 0.025]), ("orientation", [0.0, 0.0, 0.0, 1.0])):
                for value, want in zip(entry[key], expected, strict=True):
                    self.assertAlmostEqual(value, want, msg=key)
        for value, want in zip(belt["size"], [1.0, 0.3, 0.05], strict=True):
            self.assertAlmostEqual(value, want)
        self.assertAlmostEqual(belt["speed"], 0.3)
        self.assertEqual([s["name"] for s in world["sources"]], ["part"])
        self.assertEqual(world["sources"][0]["conveyor"], "belt")
        self.assertEqual([s["name"] for s in world["sinks"]], ["belt_end"])
        self.assertEqual((world["bins"], world["cameras"]), ([], []))

    def test_set_conveyor(self):
        set_conveyor = sim_service("set_conveyor", SetConveyor, TIMEOUT)
        unknown = set_conveyor("band", 0.1)
        self.assertFalse(unknown.success)
        self.assertIn("unknown conveyor 'band'", unknown.status_message)
        nan = set_conveyor("belt", math.nan)
        self.assertFalse(nan.success)
        self.assertIn("speed must be finite", nan.status_message)
        self.assertTrue(set_conveyor("belt", 0.5).success)
        states = wait_for(lambda m: list(m.speed) == [0.5], "speed 0.5", "sixdof_sim/conveyor_states", ConveyorStates)
        self.assertEqual(list(states.conveyor), ["belt"])
        self.assertAlmostEqual(states.velocity[0].x, 0.5)
        # A part a second at 0.5 m/s reaches the sink (1.1 m on) in about 2.5 s.
        states = wait_for(lambda m: m.deleted[0] >= 1, "a deleted part", "sixdof_sim/conveyor_states", ConveyorStates)
        self.assertEqual(list(states.sink), ["belt_end"])
        self.assertEqual(list(states.source), ["part"])
        self.assertGreater(states.spawned[0], states.deleted[0])
        self.assertTrue(set_conveyor("belt", 0.0).success)

    def test_vacuum_holds_and_releases(self):
        client = actionlib.SimpleActionClient("gripper_controller/gripper_cmd", GripperCommandAction)
        wait_for_servers((client,), TIMEOUT)
        goal = GripperCommandGoal()
        goal.command.position = math.nan
        client.send_goal(goal)
        self.assertTrue(wait_for_goal(client, TIMEOUT))
        self.assertEqual(client.get_state(), GoalStatus.REJECTED)

        goal.command.position = 1.0
        client.send_goal(goal)
        self.assertTrue(wait_for_goal(client, TIMEOUT))
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED)
        self.assertEqual(client.get_result().position, 1.0)
        self.assertFalse(client.get_result().stalled)

        # A 4 cm cube put 1 mm under the cup's face (0.3 m up with the lift at zero) is held as it starts to fall.
        spawn = sim_service("spawn_object", SpawnObject, TIMEOUT)
        cube = SimObject(name="cup_cube", mass=0.1, friction=0.8)
        cube.shape.type = SolidPrimitive.BOX
        cube.shape.dimensions = [0.04, 0.04, 0.04]
        cube.pose = Pose()
        cube.pose.position.z = 0.279
        cube.pose.orientation.w = 1.0
        events = []
        lock = threading.Lock()

        def on_event(msg: GraspEvent) -> None:
            with lock:
                events.append(msg)

        subscriber = rospy.Subscriber("grasp_events", GraspEvent, on_event)
        deadline = time.monotonic() + TIMEOUT
        while subscriber.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)

        def next_event() -> GraspEvent:
            while time.monotonic() < deadline:
                with lock:
                    if events:
                        return events.pop(0)
                time.sleep(0.01)
            raise AssertionError("no grasp event")

        self.assertTrue(spawn(cube).success)
        event = next_event()
        self.assertEqual(event.object, "cup_cube")
        self.assertEqual(event.event, GraspEvent.ATTACHED)
        self.assertEqual(event.palm_link, "cup")
        self.assertEqual(list(event.gripper_links), ["cup"])
        self.assertEqual(event.arm, "gantry")
        rospy.sleep(0.5)
        states = rospy.wait_for_message("sixdof_sim/object_states", ObjectStates, TIMEOUT)
        index = states.name.index("cup_cube")
        self.assertEqual(states.attached_to[index], "cup")
        self.assertAlmostEqual(states.pose[index].position.z, 0.279, delta=0.003)

        goal.command.position = 0.0
        client.send_goal(goal)
        self.assertTrue(wait_for_goal(client, TIMEOUT))
        self.assertEqual(client.get_result().position, 0.0)
        event = next_event()
        self.assertEqual(event.event, GraspEvent.DETACHED)
        self.assertEqual(event.object, "cup_cube")


if __name__ == "__main__":
    rospy.init_node("sim_conveyor")
    rostest.rosrun("sixdof_sim", "sim_conveyor", SimConveyor)
