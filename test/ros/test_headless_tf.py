#!/usr/bin/env python3
"""Headless in step (issue 13 item 9): with the simulator running as fast as it can, a tf sample of the robot
newer than the end of a motion reaches a tf consumer within 0.2 s of wall time after the motion's result."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from faults import bounded_call, connect, wait_until
from moveit_msgs.msg import ExecuteTrajectoryActionResult, ExecuteTrajectoryGoal, MotionPlanRequest, MoveItErrorCodes
from sixdof_commander.goals import joint_constraints
from tf2_msgs.msg import TFMessage

from sixdof_test_support.actions import wait_for_goal

GROUP = "arm"
MOTIONS = 4
BOUND = 0.2  # s of wall time (the requirement)


class HeadlessTf(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.group, cls.plan_service, cls.execute = connect("test_headless_tf", GROUP)
        cls.lock = threading.Lock()
        cls.tf_samples = []  # (stamp, wall arrival) of robot_state_publisher's messages
        cls.results = []  # (stamp, wall arrival) of execute_trajectory results
        rospy.Subscriber("tf", TFMessage, cls._tf, queue_size=100)
        rospy.Subscriber("execute_trajectory/result", ExecuteTrajectoryActionResult, cls._result, queue_size=10)

    @classmethod
    def _tf(cls, msg):
        if msg._connection_header.get("callerid") != "/robot_state_publisher" or not msg.transforms:
            return
        with cls.lock:
            cls.tf_samples.append((max(t.header.stamp for t in msg.transforms), time.monotonic()))

    @classmethod
    def _result(cls, msg):
        with cls.lock:
            cls.results.append((msg.header.stamp, time.monotonic()))

    def test_tf_is_current_after_every_motion(self):
        delays = []
        names = self.group.get_named_targets()
        for i in range(MOTIONS):
            # The named state as joint constraints, as MoveGroupInterface sends it.
            goal = joint_constraints(self.group.get_named_target_values(names[i % 2]), 1e-4)
            request = MotionPlanRequest(group_name=GROUP, goal_constraints=[goal])
            request.start_state.is_diff = True
            response = bounded_call(self.plan_service, request, timeout=30.0, what="plan_kinematic_path")
            error = response.motion_plan_response.error_code
            self.assertEqual(error.val, MoveItErrorCodes.SUCCESS, f"planning to '{names[i % 2]}'")
            with self.lock:
                self.results.clear()
            self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=response.motion_plan_response.trajectory))
            self.assertTrue(wait_for_goal(self.execute, 120.0), "no execute_trajectory result")
            self.assertEqual(self.execute.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
            end, ended = wait_until(lambda: self.results and self.results[-1], 10.0, "the result message")

            def newer_sample(end=end):
                with self.lock:
                    return next((wall for stamp, wall in self.tf_samples if stamp >= end), None)

            arrived = wait_until(newer_sample, 10.0, f"a tf sample newer than {end.to_sec():.3f}", period=0.005)
            delays.append(max(arrived - ended, 0.0))
            with self.lock:
                self.tf_samples[:] = [s for s in self.tf_samples if s[0] >= end]
        rospy.loginfo("tf sample newer than the motion's end, wall delay after the result: %s s",
                      ", ".join(f"{d:.3f}" for d in delays))
        for i, delay in enumerate(delays):
            self.assertLessEqual(delay, BOUND, f"motion {i}: no tf sample newer than its end within {BOUND} s")


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_headless_tf", HeadlessTf, sys.argv)
