#!/usr/bin/env python3
"""rostest: the simulator's trajectory actions follow joint_trajectory_controller semantics and error codes,
and bad requests are rejected while the node keeps serving."""

import math
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryResult,
    JointTolerance,
    JointTrajectoryControllerState,
)
from control_msgs.srv import QueryTrajectoryState
from shape_msgs.msg import SolidPrimitive
from sim_test_util import (
    ARM_JOINTS,
    FINGER_JOINTS,
    JointStateListener,
    sim_service,
    trajectory_goal,
    wait_for_servers,
)
from std_srvs.srv import Empty

from sixdof_msgs.msg import SimObject
from sixdof_msgs.srv import GetObjectState, SpawnObject
from sixdof_test_support.actions import wait_for_goal

TARGET = [0.3, -0.2, 0.4, 0.1, 0.3, -0.2]
TARGET_B = [-0.3, 0.2, 0.6, -0.1, 0.5, 0.2]
SERVER_TIMEOUT = 60.0
RESULT_TIMEOUT = 60.0  # s: wall-clock in wait_for_goal, simulated in the deadlines on rospy.Time


class SimActionsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_sim_actions")
        cls.arm = actionlib.SimpleActionClient("arm_controller/follow_joint_trajectory", FollowJointTrajectoryAction)
        cls.fingers = actionlib.SimpleActionClient(
            "gripper_controller/follow_joint_trajectory", FollowJointTrajectoryAction
        )
        wait_for_servers((cls.arm, cls.fingers), SERVER_TIMEOUT)
        cls.reset_world = sim_service("reset_world", Empty, SERVER_TIMEOUT)
        cls.spawn = sim_service("spawn_object", SpawnObject, SERVER_TIMEOUT)
        cls.get_object = sim_service("get_object_state", GetObjectState, SERVER_TIMEOUT)
        cls.joints = JointStateListener()

    def setUp(self) -> None:
        self.reset_world()

    def run_goal(self, goal, client=None) -> tuple[int, FollowJointTrajectoryResult]:
        client = client or self.arm
        client.send_goal(goal)
        self.assertTrue(wait_for_goal(client, RESULT_TIMEOUT), "no result")
        return client.get_state(), client.get_result()

    def assert_rejected(self, goal, code: int, text: str, client=None) -> None:
        state, result = self.run_goal(goal, client)
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, code, result.error_string)
        self.assertIn(text, result.error_string)

    def assert_reaches(self, joints: list[str], expected: list[float], tolerance: float) -> None:
        reached = self.joints.wait_near(joints, expected, tolerance)
        self.assertTrue(reached, f"{self.joints.positions(joints)} != {expected}")

    def test_trajectory_reaches_the_goal(self) -> None:
        feedback = []
        goal = trajectory_goal(ARM_JOINTS, [(TARGET, 1.5)])
        self.arm.send_goal(goal, feedback_cb=feedback.append)
        self.assertTrue(wait_for_goal(self.arm, RESULT_TIMEOUT))
        self.assertEqual(self.arm.get_state(), GoalStatus.SUCCEEDED)
        self.assertEqual(self.arm.get_result().error_code, FollowJointTrajectoryResult.SUCCESSFUL)
        self.assert_reaches(ARM_JOINTS, TARGET, 0.011)
        self.assertGreater(len(feedback), 10)
        self.assertEqual(feedback[-1].joint_names, ARM_JOINTS)

    def test_state_topic_reports_desired_actual_and_error(self) -> None:
        states = []
        sub = rospy.Subscriber("arm_controller/state", JointTrajectoryControllerState, states.append, queue_size=1000)
        try:
            # The simulator runs free here: a 1.5 s trajectory takes a fraction of a wall second, so the
            # subscription must be live (the holding controller publishes too) before the goal goes out.
            deadline = rospy.Time.now() + rospy.Duration(RESULT_TIMEOUT)
            while not states and rospy.Time.now() < deadline:
                rospy.rostime.wallsleep(0.01)
            self.assertTrue(states, "no state before the goal")
            del states[:]
            state, result = self.run_goal(trajectory_goal(ARM_JOINTS, [(TARGET, 1.5)]))
            self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
            self.assert_reaches(ARM_JOINTS, TARGET, 0.011)
            # Settled: the state then commands the target (the test's clock may lag the simulator's, so this
            # waits for the message rather than for a time).
            deadline = rospy.Time.now() + rospy.Duration(10.0)
            while rospy.Time.now() < deadline and not all(
                abs(d - t) < 1e-9 for d, t in zip(states[-1].desired.positions, TARGET, strict=True)
            ):
                rospy.rostime.wallsleep(0.01)
        finally:
            sub.unregister()
        self.assertGreater(len(states), 10)
        moving = [m for m in states if max(abs(v) for v in m.desired.velocities) > 0.01]
        self.assertTrue(moving, "no state while the trajectory moved")
        for m in states:
            self.assertEqual(list(m.joint_names), ARM_JOINTS)
            for d, a, e in zip(m.desired.positions, m.actual.positions, m.error.positions, strict=True):
                self.assertAlmostEqual(e, d - a, places=9)
        stamps = [m.header.stamp.to_sec() for m in states]
        # Never faster than the configured 50 Hz (state_publish_rate default), stamps in order.
        self.assertGreaterEqual(min(b - a for a, b in zip(stamps, stamps[1:], strict=False)), 0.02 - 1.5e-3)
        last = states[-1]
        self.assertTrue(all(abs(v) < 1e-9 for v in last.desired.velocities), last.desired.velocities)
        for d, a, t in zip(last.desired.positions, last.actual.positions, TARGET, strict=True):
            self.assertAlmostEqual(d, t, places=6)
            self.assertAlmostEqual(a, t, delta=0.011)

    def test_query_state_samples_the_commanded_trajectory(self) -> None:
        query = rospy.ServiceProxy("arm_controller/query_state", QueryTrajectoryState)
        answer = query(rospy.Time.now())
        self.assertEqual(list(answer.name), ARM_JOINTS)
        # Holding where the reset left the arm. The latest joint_states may still be from before the reset: wait
        # until they show the arm where the controller says it holds it.
        self.assertTrue(self.joints.wait_near(ARM_JOINTS, list(answer.position), 0.011), "arm not where it is held")
        for v in answer.velocity:
            self.assertEqual(v, 0.0)
        self.arm.send_goal(trajectory_goal(ARM_JOINTS, [(TARGET, 1.5)]))
        deadline = rospy.Time.now() + rospy.Duration(RESULT_TIMEOUT)
        while self.arm.get_state() == GoalStatus.PENDING and rospy.Time.now() < deadline:
            rospy.rostime.wallsleep(0.01)
        # Once accepted, the controller answers for any time: long after the end, the last point at rest.
        answer = query(rospy.Time.now() + rospy.Duration(100.0))
        for p, v, t in zip(answer.position, answer.velocity, TARGET, strict=True):
            self.assertAlmostEqual(p, t, places=9)
            self.assertAlmostEqual(v, 0.0, places=9)
        self.assertTrue(wait_for_goal(self.arm, RESULT_TIMEOUT))
        self.assertEqual(self.arm.get_state(), GoalStatus.SUCCEEDED)

    def test_multi_point_linear_trajectory_in_another_joint_order(self) -> None:
        order = list(reversed(ARM_JOINTS))
        mid = [0.5 * t for t in TARGET]
        goal = trajectory_goal(order, [(list(reversed(mid)), 1.0), (list(reversed(TARGET)), 2.0)], False)
        state, result = self.run_goal(goal)
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assert_reaches(ARM_JOINTS, TARGET, 0.011)

    def test_invalid_joints(self) -> None:
        goal = trajectory_goal(ARM_JOINTS[:5] + ["elbow"], [(TARGET, 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_JOINTS, "elbow")
        goal = trajectory_goal(ARM_JOINTS[:5], [(TARGET[:5], 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_JOINTS, "joint6")

    def test_invalid_goal_nan(self) -> None:
        goal = trajectory_goal(ARM_JOINTS, [([math.nan] + TARGET[1:], 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_GOAL, "NaN")

    def test_invalid_goal_out_of_limits(self) -> None:
        goal = trajectory_goal(ARM_JOINTS, [([0.0, 2.5, 0.0, 0.0, 0.0, 0.0], 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_GOAL, "joint2")

    def test_invalid_goal_non_increasing_times(self) -> None:
        goal = trajectory_goal(ARM_JOINTS, [(TARGET, 1.0), (TARGET_B, 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_GOAL, "strictly increase")

    def test_goal_tolerance_violated(self) -> None:
        goal = trajectory_goal(ARM_JOINTS, [(TARGET, 1.0)])
        goal.goal_tolerance = [JointTolerance(name=j, position=1e-9, velocity=1e-9) for j in ARM_JOINTS]
        goal.goal_time_tolerance = rospy.Duration(-1.0)  # negative: no time beyond the trajectory's end
        state, result = self.run_goal(goal)
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED, result.error_string)

    def test_path_tolerance_violated(self) -> None:
        # Far beyond the joints' effort limits: the arm cannot follow.
        goal = trajectory_goal(ARM_JOINTS, [([1.5, 1.0, -1.5, 1.0, 1.0, 1.0], 0.1)])
        goal.path_tolerance = [JointTolerance(name=j, position=0.05) for j in ARM_JOINTS]
        state, result = self.run_goal(goal)
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED, result.error_string)
        self.assertIn("path tolerance", result.error_string)

    def test_preemption(self) -> None:
        self.arm.send_goal(trajectory_goal(ARM_JOINTS, [(TARGET, 3.0)]))
        rospy.sleep(1.0)  # the behaviour under test: a goal preempted a third into its motion (simulated time)
        first = self.arm.gh  # the first goal's handle, before the client moves on
        state, result = self.run_goal(trajectory_goal(ARM_JOINTS, [(TARGET_B, 2.0)]))
        self.assertEqual(first.get_goal_status(), GoalStatus.PREEMPTED)
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assert_reaches(ARM_JOINTS, TARGET_B, 0.011)

    def test_cancel_holds_position(self) -> None:
        self.arm.send_goal(trajectory_goal(ARM_JOINTS, [(TARGET, 2.0)]))
        rospy.sleep(1.0)  # the behaviour under test: a goal canceled halfway through its motion (simulated time)
        self.arm.cancel_goal()
        self.assertTrue(wait_for_goal(self.arm, RESULT_TIMEOUT))
        self.assertEqual(self.arm.get_state(), GoalStatus.PREEMPTED)
        held = self.joints.settled(ARM_JOINTS)
        rospy.sleep(1.0)  # the behaviour under test: the joints hold where they stopped, 1 s later too
        self.assertTrue(self.joints.wait_near(ARM_JOINTS, held, 0.005, timeout=0.0))
        self.assertGreater(abs(held[0]), 0.05)  # it had moved, and stopped short of the target
        self.assertLess(abs(held[0]), abs(TARGET[0]) - 0.02)

    def test_gripper_trajectory_checks_the_mimic_finger(self) -> None:
        goal = trajectory_goal(FINGER_JOINTS, [([0.03, 0.01], 1.0)])
        self.assert_rejected(goal, FollowJointTrajectoryResult.INVALID_GOAL, "mimics", self.fingers)
        state, result = self.run_goal(trajectory_goal(FINGER_JOINTS, [([0.03, 0.03], 1.0)]), self.fingers)
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assert_reaches(FINGER_JOINTS, [0.03, 0.03], 0.0025)

    def test_bad_requests_leave_the_node_serving(self) -> None:
        bad = SimObject(name="box", shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.1]), mass=0.1)
        bad.pose.orientation.w = 1.0
        response = self.spawn(bad)
        self.assertFalse(response.success)
        self.assertIn("BOX", response.status_message)
        bad.shape.dimensions = [0.1, 0.1, 0.1]
        bad.pose.orientation.w = 0.0
        response = self.spawn(bad)
        self.assertFalse(response.success)
        self.assertIn("quaternion", response.status_message)
        response = self.get_object("no_such_object")
        self.assertFalse(response.success)
        self.assertIn("no_such_object", response.status_message)
        self.assert_rejected(
            trajectory_goal(ARM_JOINTS, [([math.inf] * 6, 1.0)]), FollowJointTrajectoryResult.INVALID_GOAL, "inf"
        )
        good = SimObject(name="box", shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.05] * 3), mass=0.1)
        good.pose.position.x, good.pose.position.y, good.pose.position.z = 0.3, 0.3, 0.5
        good.pose.orientation.w = 1.0
        good.friction = 0.8
        response = self.spawn(good)
        self.assertTrue(response.success, response.status_message)
        state, result = self.run_goal(trajectory_goal(ARM_JOINTS, [(TARGET, 1.0)]))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assertLess(self.get_object("box").object.pose.position.z, 0.5)  # it fell under gravity


if __name__ == "__main__":
    rostest.rosrun("sixdof_sim", "test_sim_actions", SimActionsTest)
