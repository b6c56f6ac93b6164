#!/usr/bin/env python3
"""rostest: the commander's wait for joint_states stamped after a time, across a jump back of ROS time (a restarted
simulator's clock starting over)."""

import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from sixdof_commander._ros import JointStateMonitor

TOPIC = "clock_jump_joint_states"


class JointStatesAcrossAClockJump(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("joint_states_clock_jump")
        cls.clock = rospy.Publisher("/clock", Clock, queue_size=1, latch=True)
        cls.states = rospy.Publisher(TOPIC, JointState, queue_size=1, latch=True)

    def set_time(self, seconds: float) -> None:
        """Publishes /clock and waits (wall clock, bounded) until this node's ROS time is there."""
        self.clock.publish(Clock(clock=rospy.Time(seconds)))
        deadline = time.monotonic() + 10.0
        while rospy.get_time() != seconds:
            self.assertLess(time.monotonic(), deadline, f"ROS time never became {seconds}")
            time.sleep(0.01)

    def publish_state(self, stamp: float) -> None:
        message = JointState(name=["joint1"], position=[stamp])
        message.header.stamp = rospy.Time(stamp)
        self.states.publish(message)

    def test_a_jump_back_forgets_the_stamps_of_before(self) -> None:
        monitor = JointStateMonitor(TOPIC)
        self.set_time(100.0)
        self.publish_state(100.0)
        self.assertTrue(monitor.wait_newer(100.0, timeout=10.0))
        self.set_time(5.0)  # the simulator restarted: its clock starts over
        # The state stamped 100 is of the timeline before: it is not one stamped after 5.
        self.assertFalse(monitor.wait_newer(rospy.get_time(), timeout=0.3))
        self.assertEqual(monitor.stamp, float("-inf"))
        self.publish_state(5.0)
        self.assertTrue(monitor.wait_newer(5.0, timeout=10.0))
        self.assertEqual(monitor.stamp, 5.0)
        self.assertEqual(monitor.positions(["joint1"]), {"joint1": 5.0})
        self.assertFalse(monitor.wait_newer(5.5, timeout=0.3))  # time moves on: an older stamp is not newer


if __name__ == "__main__":
    rostest.rosrun("sixdof_scripts", "joint_states_clock_jump", JointStatesAcrossAClockJump)
