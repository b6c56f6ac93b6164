#!/usr/bin/env python3
"""End-to-end pick and place through the whole headless stack: for several start and place positions the
cube ends upright within 1 cm of the place target; the grasp fix attaches and releases it (grasp_events); the
planning scene holds it attached to link6 (fingers as touch links) while carried and in the world after."""

import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from e2e import case, object_at_rest, object_state, planning_scene, settled_joint_state, wait_for_stack
from geometry_msgs.msg import Pose, Twist
from sixdof_commander import ArmDriver

from sixdof_bringup.placement import placement
from sixdof_msgs.msg import GraspEvent
from sixdof_msgs.srv import SetObjectState

CUBE = "red_cube"
HALF_HEIGHT = 0.02
# (start x, y) -> (place x, y) on the table, clear of the other objects of table_top.yaml.
CASES = [
    ((0.40, -0.15), (0.40, 0.20)),
    ((0.32, 0.05), (0.45, -0.05)),
    ((0.45, 0.25), (0.30, -0.20)),
]


class EndToEndPickPlace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_pick_place")
        wait_for_stack(CUBE)
        cls.driver = ArmDriver(wait_for_servers=60.0)
        cls.events = []
        cls.lock = threading.Lock()
        rospy.Subscriber("grasp_events", GraspEvent, cls.on_event, queue_size=100)
        cls.set_state = rospy.ServiceProxy("sixdof_sim/set_object_state", SetObjectState)

    @classmethod
    def on_event(cls, msg):
        with cls.lock:
            cls.events.append(msg)

    def put_cube(self, x: float, y: float) -> None:
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = x, y, HALF_HEIGHT
        pose.orientation.w = 1.0
        response = self.set_state(CUBE, pose, Twist())
        self.assertTrue(response.success, response.status_message)
        # At rest before planning around it.
        settled_joint_state()
        object_at_rest(CUBE)
        self.assert_in_world_at(x, y)

    def test_pick_and_place_at_several_positions(self):
        for (sx, sy), (px, py) in CASES:
            with case(start=(sx, sy), place=(px, py)):
                self.assertTrue(self.driver.moveto_named("home pose"), self.driver.last_failure)
                self.put_cube(sx, sy)
                with self.lock:
                    self.events.clear()
                self.assertTrue(self.driver.grasp(CUBE), self.driver.last_failure)
                self.assertTrue(self.driver.lift(), self.driver.last_failure)
                held = object_state(CUBE)
                self.assertEqual(held.attached_to, "link6", "the grasp fix holds the lifted cube")
                self.assert_attached_in_scene()
                self.assertTrue(self.driver.release_at([px, py, HALF_HEIGHT]), self.driver.last_failure)
                self.assertTrue(self.driver.retreat(), self.driver.last_failure)
                settled_joint_state()
                final = object_at_rest(CUBE)
                self.assertEqual(final.attached_to, "")
                result = placement(final.object.pose, (px, py, HALF_HEIGHT))
                rospy.loginfo(
                    "pick (%.2f, %.2f) -> place (%.2f, %.2f): error %.1f mm, tilt %.2f deg",
                    sx,
                    sy,
                    px,
                    py,
                    result.error * 1e3,
                    math.degrees(result.tilt),
                )
                self.assertLess(result.error, 0.01)
                self.assertLess(math.degrees(result.tilt), 5.0)
                self.assert_grasp_events()
                self.assert_in_world_at(px, py)

    def assert_attached_in_scene(self):
        attached = {a.object.id: a for a in planning_scene().robot_state.attached_collision_objects}
        self.assertIn(CUBE, attached)
        self.assertEqual(attached[CUBE].link_name, "link6")
        self.assertTrue({"finger1", "finger2"} <= set(attached[CUBE].touch_links))

    def assert_grasp_events(self):
        with self.lock:
            kinds = [(e.event, e.object) for e in self.events]
            attach = [e for e in self.events if e.event == GraspEvent.ATTACHED]
        self.assertEqual(kinds, [(GraspEvent.ATTACHED, CUBE), (GraspEvent.DETACHED, CUBE)])
        self.assertEqual(attach[0].palm_link, "link6")
        self.assertEqual(sorted(attach[0].gripper_links), ["finger1", "finger2"])

    def assert_in_world_at(self, x, y):
        # The scene mirror moves the cube to where it rests; it runs on the wall clock (the simulator may run
        # free), so this hang guard does too.
        deadline = time.monotonic() + 15.0
        while True:
            world = {o.id: o.pose.position for o in planning_scene().world.collision_objects}
            if CUBE in world and math.dist((world[CUBE].x, world[CUBE].y), (x, y)) < 0.01:
                return
            if time.monotonic() > deadline:
                self.fail(f"planning scene has {CUBE} at {world.get(CUBE)}, not near ({x}, {y})")
            time.sleep(0.1)


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_pick_place", EndToEndPickPlace, sys.argv)
