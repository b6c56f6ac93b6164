#!/usr/bin/env python3
"""rostest (driver.test): the sixdof_control driver node on the mock plugin serves the controllers as the simulator
does (joint_trajectory_controller semantics, state topics, query_state, gripper_cmd, mimic joints), refuses what the
control loop refuses (a start away from the joints, limits, e-stop, faults), and reports faults within 1 s naming
the joint or device. Wall clock; bounds are outcomes (a result came), not speed claims."""

import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    FollowJointTrajectoryResult,
    GripperCommandAction,
    GripperCommandGoal,
    JointTrajectoryControllerState,
)
from control_msgs.srv import QueryTrajectoryState
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from sensor_msgs.msg import JointState
from std_srvs.srv import SetBool, Trigger
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_test_support.actions import wait_for_goal

ARM = [f"joint{i}" for i in range(1, 7)]
FINGERS = ["finger1_joint", "finger2_joint"]
TARGET = [0.3, -0.2, 0.4, 0.1, 0.3, -0.2]
TIMEOUT = 60.0
FAULT_BOUND = 1.0  # s from the fault to the goal's end (docs/real_robot.md)
FAULT_AFTER = 1.0  # s into the first motion: the mock's lost_after / unresponsive_after (driver.test)


def goal_to(joints: list[str], points: list[tuple[list[float], float]]) -> FollowJointTrajectoryGoal:
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(joints)
    for positions, t in points:
        goal.trajectory.points.append(
            JointTrajectoryPoint(positions=list(positions), velocities=[0.0] * len(positions),
                                 time_from_start=rospy.Duration(t))
        )
    return goal


class Joints:
    """The latest joint_states of a namespace."""

    def __init__(self, ns: str = "") -> None:
        self._lock = threading.Lock()
        self._msg = None
        self._sub = rospy.Subscriber(f"{ns}/joint_states", JointState, self._callback, queue_size=1)

    def _callback(self, msg: JointState) -> None:
        with self._lock:
            self._msg = msg

    def get(self, names: list[str]) -> list[float]:
        deadline = time.monotonic() + TIMEOUT
        while self._msg is None:
            assert time.monotonic() < deadline, "no joint_states"
            time.sleep(0.01)
        with self._lock:
            positions = dict(zip(self._msg.name, self._msg.position, strict=True))
        return [positions[n] for n in names]


class Driver:
    """Clients of one driver's namespace."""

    def __init__(self, ns: str = "") -> None:
        self.arm = actionlib.SimpleActionClient(f"{ns}/arm_controller/follow_joint_trajectory",
                                                FollowJointTrajectoryAction)
        self.fingers = actionlib.SimpleActionClient(f"{ns}/gripper_controller/follow_joint_trajectory",
                                                    FollowJointTrajectoryAction)
        self.gripper = actionlib.SimpleActionClient(f"{ns}/gripper_controller/gripper_cmd", GripperCommandAction)
        for client in (self.arm, self.fingers, self.gripper):
            assert client.wait_for_server(rospy.Duration(TIMEOUT)), "driver action server missing"
        rospy.wait_for_service(f"{ns}/sixdof_control/estop", TIMEOUT)
        self.estop = rospy.ServiceProxy(f"{ns}/sixdof_control/estop", SetBool)
        self.clear_fault = rospy.ServiceProxy(f"{ns}/sixdof_control/clear_fault", Trigger)
        self.query = rospy.ServiceProxy(f"{ns}/arm_controller/query_state", QueryTrajectoryState)
        self.joints = Joints(ns)

    def run(self, client, goal) -> tuple[int, object]:
        client.send_goal(goal)
        assert wait_for_goal(client, TIMEOUT), "no result"
        return client.get_state(), client.get_result()

    def arm_goal(self, target: list[float], seconds: float) -> FollowJointTrajectoryGoal:
        return goal_to(ARM, [(target, seconds)])


class DriverTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_driver")
        cls.driver = Driver()

    def setUp(self) -> None:
        d = self.driver
        d.estop(False)
        state, result = d.run(d.arm, d.arm_goal([0.0] * 6, 1.0))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)

    def assert_near(self, names: list[str], expected: list[float], tolerance: float) -> None:
        deadline = time.monotonic() + 5.0
        while True:
            reached = self.driver.joints.get(names)
            if all(abs(a - b) <= tolerance for a, b in zip(reached, expected, strict=True)):
                return
            self.assertLess(time.monotonic(), deadline, f"{reached} != {expected}")
            time.sleep(0.02)

    def test_trajectory_state_topic_and_query_state(self) -> None:
        d = self.driver
        states = []
        sub = rospy.Subscriber("arm_controller/state", JointTrajectoryControllerState, states.append, queue_size=100)
        try:
            state, result = d.run(d.arm, d.arm_goal(TARGET, 1.5))
        finally:
            sub.unregister()
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.SUCCESSFUL)
        self.assert_near(ARM, TARGET, 0.011)
        self.assertGreater(len(states), 10)
        for m in states:
            self.assertEqual(list(m.joint_names), ARM)
            for desired, actual, error in zip(m.desired.positions, m.actual.positions, m.error.positions,
                                              strict=True):
                self.assertAlmostEqual(error, desired - actual, places=9)
        answer = d.query(rospy.Time.now() + rospy.Duration(100.0))
        self.assertEqual(list(answer.name), ARM)
        for p, t in zip(answer.position, TARGET, strict=True):
            self.assertAlmostEqual(p, t, places=9)

    def test_preemption(self) -> None:
        d = self.driver
        d.arm.send_goal(d.arm_goal(TARGET, 3.0))
        rospy.rostime.wallsleep(0.5)
        first = d.arm.gh
        state, result = d.run(d.arm, d.arm_goal([-t for t in TARGET], 2.0))
        self.assertEqual(first.get_goal_status(), GoalStatus.PREEMPTED)
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)

    def test_refusals_start_state_limits_unknown_joint(self) -> None:
        d = self.driver
        cases = [
            (goal_to(ARM, [([1.0] + [0.0] * 5, 0.0), (TARGET, 1.0)]), FollowJointTrajectoryResult.INVALID_GOAL,
             "start_tolerance"),
            (d.arm_goal([0.0, 2.5, 0.0, 0.0, 0.0, 0.0], 2.0), FollowJointTrajectoryResult.INVALID_GOAL, "joint2"),
            (d.arm_goal([1.5] + [0.0] * 5, 0.1), FollowJointTrajectoryResult.INVALID_GOAL, "velocity"),
            (goal_to(ARM[:5] + ["elbow"], [(TARGET, 1.0)]), FollowJointTrajectoryResult.INVALID_JOINTS, "elbow"),
        ]
        for goal, code, text in cases:
            state, result = d.run(d.arm, goal)
            self.assertEqual(state, GoalStatus.REJECTED, text)
            self.assertEqual(result.error_code, code, result.error_string)
            self.assertIn(text, result.error_string)

    def test_mimic_finger_follows_and_is_checked(self) -> None:
        d = self.driver
        state, result = d.run(d.fingers, goal_to(FINGERS, [([0.03, 0.01], 1.0)]))
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertIn("mimics", result.error_string)
        state, result = d.run(d.fingers, goal_to(FINGERS[:1], [([0.03], 1.0)]))
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.INVALID_JOINTS, result.error_string)
        state, result = d.run(d.fingers, goal_to(FINGERS, [([0.03, 0.03], 1.0)]))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)
        self.assert_near(FINGERS, [0.03, 0.03], 0.0025)

    def test_gripper_cmd_takes_the_finger_from_the_trajectory_controller(self) -> None:
        d = self.driver
        d.fingers.send_goal(goal_to(FINGERS, [([0.04, 0.04], 3.0)]))
        rospy.rostime.wallsleep(0.3)
        state, result = d.run(d.gripper, GripperCommandGoal())  # position 0: closed
        self.assertEqual(d.fingers.get_state(), GoalStatus.PREEMPTED)
        self.assertEqual(state, GoalStatus.SUCCEEDED)
        self.assertTrue(result.reached_goal)
        self.assertLess(abs(result.position), 0.0025)
        query = rospy.ServiceProxy("gripper_controller/query_state", QueryTrajectoryState)
        with self.assertRaises(rospy.ServiceException):  # gripper_cmd commands the finger now
            query(rospy.Time.now())
        state, result = d.run(d.fingers, goal_to(FINGERS, [([0.02, 0.02], 1.0)]))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)

    def test_estop_stops_motion_and_refuses_goals_until_released(self) -> None:
        d = self.driver
        d.arm.send_goal(d.arm_goal(TARGET, 3.0))
        rospy.rostime.wallsleep(1.0)
        pressed = time.monotonic()
        self.assertTrue(d.estop(True).success)
        self.assertTrue(wait_for_goal(d.arm, TIMEOUT), "no result")
        self.assertLess(time.monotonic() - pressed, FAULT_BOUND)
        self.assertEqual(d.arm.get_state(), GoalStatus.ABORTED)
        self.assertIn("e-stop", d.arm.get_result().error_string)
        rospy.rostime.wallsleep(0.2)
        held = d.joints.get(ARM)
        rospy.rostime.wallsleep(0.5)
        self.assertTrue(all(abs(a - b) < 1e-3 for a, b in zip(d.joints.get(ARM), held, strict=True)), "still moving")
        self.assertGreater(abs(held[0]), 0.01)  # it had moved, and stopped short of the target
        self.assertLess(abs(held[0]), abs(TARGET[0]) - 0.02)
        state, result = d.run(d.arm, d.arm_goal(TARGET, 2.0))
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertIn("e-stop", result.error_string)
        state, _ = d.run(d.gripper, GripperCommandGoal())
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertTrue(d.estop(False).success)
        state, result = d.run(d.arm, d.arm_goal(TARGET, 2.0))
        self.assertEqual(state, GoalStatus.SUCCEEDED, result.error_string)

    def test_diagnostics_carry_the_period_statistics(self) -> None:
        # The three drivers publish on /diagnostics: one subscriber, kept for the whole wait, sees every driver's
        # messages until this driver's status comes.
        found = threading.Event()
        statuses: list[DiagnosticStatus] = []

        def keep(msg: DiagnosticArray) -> None:
            for s in msg.status:
                if s.name == "/sixdof_control: control loop" and not found.is_set():
                    statuses.append(s)
                    found.set()

        sub = rospy.Subscriber("/diagnostics", DiagnosticArray, keep)
        try:
            self.assertTrue(found.wait(TIMEOUT), "no diagnostics of /sixdof_control")
        finally:
            sub.unregister()
        status = statuses[0]
        self.assertEqual(status.level, DiagnosticStatus.OK, status.message)
        values = {kv.key: float(kv.value) for kv in status.values}
        self.assertEqual(values["rate (Hz)"], 100.0)
        for key in ("period p50 (ms)", "period p99 (ms)", "period error p50 (ms)", "period error p99 (ms)"):
            self.assertGreater(values[key], 0.0, key)

    def fault_mid_motion(self, ns: str, named: str) -> None:
        d = Driver(ns)
        d.arm.send_goal(d.arm_goal(TARGET, 3.0))
        deadline = time.monotonic() + TIMEOUT
        while d.arm.get_state() == GoalStatus.PENDING:
            self.assertLess(time.monotonic(), deadline)
            time.sleep(0.005)
        accepted = time.monotonic()
        self.assertTrue(wait_for_goal(d.arm, TIMEOUT), "no result")
        ended = time.monotonic() - accepted
        result = d.arm.get_result()
        self.assertEqual(d.arm.get_state(), GoalStatus.ABORTED, result.error_string)
        self.assertIn(named, result.error_string)
        # The fault came FAULT_AFTER s into the motion, the goal ended within FAULT_BOUND s of it.
        self.assertGreater(ended, FAULT_AFTER - 0.1, result.error_string)
        self.assertLess(ended, FAULT_AFTER + FAULT_BOUND, result.error_string)
        state, result = d.run(d.arm, d.arm_goal([0.0] * 6, 2.0))
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertIn("hardware fault", result.error_string)
        self.assertTrue(d.clear_fault().success)
        # The device is still gone: the next read faults again.
        rospy.rostime.wallsleep(0.2)
        state, result = d.run(d.arm, d.arm_goal([0.0] * 6, 2.0))
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertIn("hardware fault", result.error_string)

    def test_device_lost_mid_motion(self) -> None:
        self.fault_mid_motion("/lost", "joint1")

    def test_joint_that_stops_answering_mid_motion(self) -> None:
        self.fault_mid_motion("/unresponsive", "joint3")


if __name__ == "__main__":
    rostest.rosrun("sixdof_control", "test_driver", DriverTest)
