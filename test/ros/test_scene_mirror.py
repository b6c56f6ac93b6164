#!/usr/bin/env python3
"""scene_mirror in the headless stack: the simulator's objects are in move_group's planning scene at the
simulator's poses (the table lowered by the support clearance), the visual-only marker is not, and an object
moved in the simulator is moved in the scene."""

import math
import sys
import time
import unittest

import rospy
import rostest
from e2e import assert_scene_mirrors_simulator, case, planning_scene, wait_for_stack
from geometry_msgs.msg import Pose, Twist

from sixdof_msgs.srv import SetObjectState

SUPPORT_CLEARANCE = 0.002  # scene_mirror's default


def position(pose: Pose) -> tuple:
    return (pose.position.x, pose.position.y, pose.position.z)


class SceneMirrorInTheStack(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_scene_mirror")
        wait_for_stack()

    def test_objects_are_mirrored_at_the_simulator_poses(self):
        world, states = assert_scene_mirrors_simulator(self, SUPPORT_CLEARANCE)
        for name, sim in states.items():
            with case(object=name):
                self.assertEqual(list(world[name].primitives[0].dimensions), list(sim.shape.dimensions))

    def test_an_object_moved_in_the_simulator_moves_in_the_scene(self):
        target = Pose()
        target.position.x, target.position.y, target.position.z = 0.30, 0.10, 0.02
        target.orientation.w = 1.0
        set_state = rospy.ServiceProxy("sixdof_sim/set_object_state", SetObjectState)
        response = set_state("red_cube", target, Twist())
        self.assertTrue(response.success, response.status_message)
        # Hang guard on the wall clock: the mirror runs on it (the simulator runs free).
        deadline = time.monotonic() + 15.0
        while True:
            world = {o.id: o.pose for o in planning_scene().world.collision_objects}
            if math.dist(position(world["red_cube"]), (0.30, 0.10, 0.02)) < 0.003:
                break
            self.assertLess(time.monotonic(), deadline, f"red_cube still at {position(world['red_cube'])}")
            time.sleep(0.1)


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_scene_mirror", SceneMirrorInTheStack, sys.argv)
