#!/usr/bin/env python3
"""Faults of the simulator while move_group executes (issue 13): the simulator stopped (SIGSTOP: /clock and
joint_states stand still, its action server stays connected) and killed (SIGKILL, respawned by roslaunch) 1.5 s
into a slow motion. Each execution must end within MoveIt's bound (expected x 1.2 + 0.5 s of wall time) with
CONTROL_FAILED naming the cause; move_group must keep answering meanwhile, and the next motion must work once the
simulator is back, with no restart of move_group. The bounds are outcomes (returned within N s), not speed claims."""

import math
import os
import signal
import sys
import time
import unittest

import rospy
import rostest
from e2e import case
from faults import bounded_call, connect, node_pid, signal_node, wait_until
from moveit_msgs.msg import ExecuteTrajectoryGoal, MotionPlanRequest, MoveItErrorCodes
from sensor_msgs.msg import JointState
from sixdof_commander.goals import joint_constraints

from sixdof_test_support.actions import wait_for_goal

SIM = "/sixdof_sim"
MOVE_GROUP = "/move_group"
GROUP = "arm"
VELOCITY_SCALING = 0.1  # a motion of several seconds: the fault lands in its middle
FAULT_AFTER = 1.5  # s of wall time into the execution
# The result reaches this test through actionlib on a loaded machine: delivery slack on top of the node's bound.
DELIVERY_SLACK = 1.0
CALL_TIMEOUT = 20.0  # a request that has not returned by then hangs


class Faults(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.group, cls.plan_service, cls.execute = connect("test_faults", GROUP)
        cls.scaling = float(rospy.get_param("move_group/allowed_execution_duration_scaling", 1.2))
        cls.margin = float(rospy.get_param("move_group/allowed_goal_duration_margin", 0.5))
        cls.move_group_pid = node_pid(MOVE_GROUP)
        cls.last_joint_state = 0.0
        rospy.Subscriber("joint_states", JointState, cls._joint_state)

    @classmethod
    def _joint_state(cls, msg):
        cls.last_joint_state = time.monotonic()
        cls.joint_state = msg

    def plan(self, target: str = "") -> tuple[object, float]:
        """A motion of the group to target (default: the named state farthest from the current one), planned from
        the current state: (trajectory, expected duration)."""
        if not target:
            current = dict(zip(self.group.get_active_joints(), self.group.get_current_joint_values(), strict=True))

            def distance(name):
                values = self.group.get_named_target_values(name)
                return math.dist([values[j] for j in current], list(current.values()))

            target = max(self.group.get_named_targets(), key=distance)
        # The named state as joint constraints, as MoveGroupInterface sends it.
        goal = joint_constraints(self.group.get_named_target_values(target), 1e-4)
        request = MotionPlanRequest(group_name=GROUP, goal_constraints=[goal])
        request.start_state.is_diff = True
        request.max_velocity_scaling_factor = VELOCITY_SCALING
        request.max_acceleration_scaling_factor = VELOCITY_SCALING
        response = bounded_call(self.plan_service, request, timeout=CALL_TIMEOUT, what="plan_kinematic_path")
        result = response.motion_plan_response
        self.assertEqual(result.error_code.val, MoveItErrorCodes.SUCCESS, f"planning to '{target}'")
        points = result.trajectory.joint_trajectory.points
        return result.trajectory, points[-1].time_from_start.to_sec()

    def allowed(self, expected: float) -> float:
        return expected * self.scaling + self.margin

    def execute_with_fault(self, sig: signal.Signals) -> tuple[float, object, str, float, int]:
        """Starts a slow motion, sends sig to the simulator FAULT_AFTER s into it and waits for the execution's
        result: (wall seconds from the goal to the result, result, its status text, allowed duration, the
        simulator's pid)."""
        trajectory, expected = self.plan()
        allowed = self.allowed(expected)
        self.assertGreater(expected, FAULT_AFTER + 1.0, "the motion must outlast the fault's delay")
        start = time.monotonic()
        self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=trajectory))
        time.sleep(FAULT_AFTER)
        pid = signal_node(SIM, sig)
        # Hang guard far above the bound: the bound itself is asserted on the measured time below.
        self.assertTrue(wait_for_goal(self.execute, allowed + 60.0), "no execute_trajectory result after the fault")
        elapsed = time.monotonic() - start
        text = self.execute.get_goal_status_text()
        rospy.loginfo("%s %.1f s into a %.1f s motion: execution ended after %.2f s (bound %.2f s): %s",
                      sig.name, FAULT_AFTER, expected, elapsed, allowed, text)
        return elapsed, self.execute.get_result(), text, allowed, pid

    def assert_failed_in_bound(self, elapsed, result, text, allowed, causes):
        self.assertIn(result.error_code.val, (MoveItErrorCodes.CONTROL_FAILED, MoveItErrorCodes.TIMED_OUT))
        self.assertTrue(any(c in text for c in causes), f"'{text}' names none of {causes}")
        self.assertLessEqual(elapsed, allowed + DELIVERY_SLACK, "the execution outlived MoveIt's bound")

    def move_group_state_is_current(self) -> bool:
        """Whether move_group plans from the simulator's present state (not the last one it heard of before)."""
        trajectory, _ = self.plan()
        start = trajectory.joint_trajectory.points[0]
        current = dict(zip(self.joint_state.name, self.joint_state.position, strict=True))
        names = trajectory.joint_trajectory.joint_names
        return all(abs(current[n] - p) < 1e-3 for n, p in zip(names, start.positions, strict=True))

    def assert_next_motion_works(self):
        wait_until(lambda: time.monotonic() - self.last_joint_state < 0.5, 60.0, "joint_states again")
        # move_group picks up the simulator's state on its own (the hang guard is far above the seconds it takes).
        wait_until(self.move_group_state_is_current, 60.0, "move_group planning from the simulator's state", 0.2)
        trajectory, expected = self.plan()
        self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=trajectory))
        self.assertTrue(wait_for_goal(self.execute, self.allowed(expected) + 60.0), "execute_trajectory after recovery")
        result = self.execute.get_result()
        self.assertEqual(result.error_code.val, MoveItErrorCodes.SUCCESS, self.execute.get_goal_status_text())

    def assert_move_group_serves(self):
        """move_group is the same process and plans (from the last known state) while the simulator is silent."""
        self.assertEqual(node_pid(MOVE_GROUP), self.move_group_pid, "move_group was restarted")
        self.plan()

    def test_1_stopped_simulator_ends_the_execution_and_move_group_keeps_answering(self):
        elapsed, result, text, allowed, pid = self.execute_with_fault(signal.SIGSTOP)
        try:
            with case(fault="SIGSTOP"):
                self.assert_failed_in_bound(
                    elapsed, result, text, allowed, ("/clock has not advanced", "joint_states stale")
                )
            with case(fault="SIGSTOP", check="planning while stopped"):
                self.assert_move_group_serves()
            with case(fault="SIGSTOP", check="executing while stopped"):
                # Executing from a state nobody confirms is refused, naming why.
                trajectory, expected = self.plan()
                self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=trajectory))
                self.assertTrue(wait_for_goal(self.execute, CALL_TIMEOUT), "execute_trajectory while stopped")
                error, text = self.execute.get_result().error_code, self.execute.get_goal_status_text()
                self.assertEqual(error.val, MoveItErrorCodes.CONTROL_FAILED, text)
                self.assertIn("no current robot state: joint_states stale for", text)
        finally:
            os.kill(pid, signal.SIGCONT)
        with case(fault="SIGSTOP", check="next motion"):
            self.assert_next_motion_works()

    def test_2_killed_simulator_ends_the_execution_and_a_respawned_one_is_picked_up(self):
        elapsed, result, text, allowed, pid = self.execute_with_fault(signal.SIGKILL)
        with case(fault="SIGKILL"):
            self.assert_failed_in_bound(
                elapsed, result, text, allowed, ("lost", "/clock has not advanced", "joint_states stale")
            )
        with case(fault="SIGKILL", check="planning while dead"):
            self.assert_move_group_serves()
        with case(fault="SIGKILL", check="respawned"):
            wait_until(lambda: node_pid(SIM) != pid, 120.0, "the simulator respawned")
        with case(fault="SIGKILL", check="next motion"):
            self.assert_next_motion_works()
        self.assertEqual(node_pid(MOVE_GROUP), self.move_group_pid, "move_group was restarted")


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_faults", Faults, sys.argv)
