#!/usr/bin/env python3
"""End-to-end pick and place with the suction cup: ArmDriver on the sixdof arm's suction variant puts the cup's face
(the TCP) on the cube's top face, turns the vacuum on (the cup holds it: ATTACHED from the cup frame), carries it
and lets go with the vacuum off (DETACHED); the cube rests upright within 1 cm of the place target."""

import math
import sys
import threading
import unittest

import rospy
import rostest
from e2e import case, object_at_rest, object_state, settled_joint_state, wait_for_stack
from geometry_msgs.msg import Pose, Twist
from sixdof_commander import ArmDriver
from sixdof_commander.suction import SuctionGripper

from sixdof_bringup.placement import placement
from sixdof_msgs.msg import GraspEvent
from sixdof_msgs.srv import SetObjectState

CUBE = "red_cube"
HALF_HEIGHT = 0.02
CASES = [((0.40, -0.15), (0.40, 0.20)), ((0.40, 0.20), (0.32, -0.05))]


class GraspEvents:
    """The grasp_events since the last clear(), as (event, object, palm link)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._seen: list[tuple[int, str, str]] = []
        rospy.Subscriber("grasp_events", GraspEvent, self._add, queue_size=100)

    def _add(self, msg: GraspEvent) -> None:
        with self._lock:
            self._seen.append((msg.event, msg.object, msg.palm_link))

    def clear(self) -> list[tuple[int, str, str]]:
        with self._lock:
            seen, self._seen = self._seen, []
        return seen


def cube_at(x: float, y: float) -> None:
    """The cube moved to (x, y) on the table, at rest, the arm still."""
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z, pose.orientation.w = x, y, HALF_HEIGHT, 1.0
    response = rospy.ServiceProxy("sixdof_sim/set_object_state", SetObjectState)(CUBE, pose, Twist())
    assert response.success, response.status_message
    settled_joint_state()
    object_at_rest(CUBE)


class SuctionPickPlace(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_suction_pick_place")
        wait_for_stack(CUBE)
        cls.driver = ArmDriver(wait_for_servers=60.0)
        cls.events = GraspEvents()

    def test_the_cup_picks_and_places_the_cube(self):
        self.assertIsInstance(self.driver.gripper, SuctionGripper)
        cup = self.driver.gripper_model.suction_cup
        for (sx, sy), (px, py) in CASES:
            with case(start=(sx, sy), place=(px, py)):
                self.assertTrue(self.driver.moveto_named(self.driver.home), self.driver.last_failure)
                cube_at(sx, sy)
                self.events.clear()
                picked = self.driver.pick(CUBE)  # top face under the cup, vacuum on, lift
                self.assertTrue(picked, self.driver.last_failure)
                self.assertEqual(object_state(CUBE).attached_to, cup, "the cup holds the lifted cube")
                placed = self.driver.place([px, py, HALF_HEIGHT])  # down, vacuum off, retreat
                self.assertTrue(placed, self.driver.last_failure)
                settled_joint_state()
                final = object_at_rest(CUBE)
                result = placement(final.object.pose, (px, py, HALF_HEIGHT))
                rospy.loginfo("suction (%.2f, %.2f) -> (%.2f, %.2f): %.1f mm, %.2f deg off", sx, sy, px, py,
                              result.error * 1e3, math.degrees(result.tilt))
                self.assertEqual((final.attached_to, result.error < 0.01, math.degrees(result.tilt) < 5.0),
                                 ("", True, True), f"placed {result.error * 1e3:.1f} mm off")
                attach, detach = GraspEvent.ATTACHED, GraspEvent.DETACHED
                self.assertEqual(self.events.clear(), [(attach, CUBE, cup), (detach, CUBE, cup)])

    def test_the_cup_on_nothing_holds_nothing(self):
        """Vacuum on in the air: sealed on nothing; off again."""
        self.assertTrue(self.driver.moveto_named(self.driver.home), self.driver.last_failure)
        self.assertFalse(self.driver.gripper.grasp().stalled)
        self.assertTrue(self.driver.gripper.release().reached_goal)


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_suction_pick_place", SuctionPickPlace, sys.argv)
