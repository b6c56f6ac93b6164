#!/usr/bin/env python3
"""rostest: the commander's errors when its servers or parameters are missing, joint_states reading (and waiting
for a state stamped after a given time), and how it matches move_group's error reports to its calls."""

import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import GripperCommandAction, GripperCommandFeedback, GripperCommandGoal
from moveit_msgs.msg import MoveItErrorCodes
from sensor_msgs.msg import JointState
from sixdof_commander import ArmDriver, Gripper, MoveGroup, PlanningScene, SixdofCommanderError
from sixdof_commander._ros import ActionClient, JointStateMonitor
from sixdof_commander.error_reports import ErrorReports

from sixdof_msgs.msg import ErrorReport


class _FastServerHandle:
    """Stands in for actionlib's ClientGoalHandle of a goal the server has already accepted."""

    def get_comm_state(self) -> int:
        return actionlib.CommState.ACTIVE

    def get_goal_status(self) -> int:
        return GoalStatus.ACTIVE


def send_with_fast_reply(client: actionlib.SimpleActionClient) -> tuple[list, list, list]:
    """Sends a goal whose first status and feedback arrive (on another thread) before the underlying
    ActionClient.send_goal returns, as a fast server's can (ros/actionlib#206). Returns what the client's
    callbacks received and the errors actionlib logged."""
    errors, active, feedback = [], [], []
    real_send = client.action_client.send_goal
    logerr = actionlib.simple_action_client.rospy.logerr

    def fast_send(goal, transition_cb, feedback_cb):
        handle = _FastServerHandle()
        reply = threading.Thread(
            target=lambda: (transition_cb(handle), feedback_cb(handle, GripperCommandFeedback(position=0.01)))
        )
        reply.start()
        reply.join(0.5)  # the reply is in before send_goal returns (unless the client makes it wait)
        return handle

    client.action_client.send_goal = fast_send
    actionlib.simple_action_client.rospy.logerr = lambda *args, **kwargs: errors.append(args)
    try:
        client.send_goal(GripperCommandGoal(), active_cb=lambda: active.append(True), feedback_cb=feedback.append)
        deadline = rospy.get_time() + 5.0
        while not feedback and rospy.get_time() < deadline:
            rospy.rostime.wallsleep(0.01)
    finally:
        client.action_client.send_goal = real_send
        actionlib.simple_action_client.rospy.logerr = logerr
    return errors, active, feedback


class CommanderWithoutServers(unittest.TestCase):
    def test_move_group_names_every_missing_server(self):
        with self.assertRaises(SixdofCommanderError) as raised:
            MoveGroup("arm", wait_for_servers=0.5)
        message = str(raised.exception)
        for name in (
            "action '/move_group'",
            "action '/execute_trajectory'",
            "service '/plan_kinematic_path'",
            "service '/compute_fk'",
            "service '/compute_cartesian_path'",
            "service '/get_planning_scene'",
            "service '/apply_planning_scene'",
            "service '/get_robot_model'",
            "service '/retime_trajectory'",
        ):
            self.assertIn(name, message)
        self.assertIn("not available after 0.5 s", message)

    def test_namespace_prefixes_the_server_names(self):
        rospy.set_param("/robot2/robot_description", rospy.get_param("/robot_description"))
        rospy.set_param("/robot2/robot_description_semantic", rospy.get_param("/robot_description_semantic"))
        with self.assertRaisesRegex(SixdofCommanderError, "action '/robot2/move_group'"):
            MoveGroup("arm", ns="/robot2", wait_for_servers=0.2)

    def test_planning_scene_and_gripper_name_their_servers(self):
        with self.assertRaisesRegex(SixdofCommanderError, "PlanningScene: service '/apply_planning_scene'"):
            PlanningScene(wait_for_servers=0.2)
        with self.assertRaisesRegex(SixdofCommanderError, "Gripper: action '/gripper_controller/gripper_cmd'"):
            Gripper(wait_for_servers=0.2)

    def test_arm_driver_without_servers(self):
        # The robot's groups and gripper come from move_group's model first.
        with self.assertRaisesRegex(SixdofCommanderError, "ArmDriver: service '/get_robot_model' not available"):
            ArmDriver(wait_for_servers=0.2)

    def test_bad_arguments_name_the_problem(self):
        with self.assertRaisesRegex(SixdofCommanderError, "wait_for_servers must be a finite number of seconds >= 0"):
            MoveGroup("arm", wait_for_servers=-1.0)
        # The groups are move_group's (get_robot_model): /stuck has one.
        with self.assertRaisesRegex(SixdofCommanderError, "no group 'manipulator'"):
            MoveGroup("manipulator", ns="/stuck", wait_for_servers=60.0)
        with self.assertRaisesRegex(SixdofCommanderError, "service '/elsewhere/get_robot_model'"):
            MoveGroup("arm", ns="/elsewhere", wait_for_servers=0.2)
        with self.assertRaisesRegex(SixdofCommanderError, "robot_description 'other_description'.*not supported"):
            MoveGroup("arm", ns="/stuck", wait_for_servers=60.0, robot_description="other_description")

    def test_scaling_factors_read_back(self):
        # What plans, Cartesian paths and ArmDriver's blended motions are timed with: one value, the MoveGroup's.
        arm = MoveGroup("arm", ns="/stuck", wait_for_servers=60.0)
        scaling = (arm.get_max_velocity_scaling_factor(), arm.get_max_acceleration_scaling_factor())
        self.assertEqual(scaling, (0.1, 0.1))  # MoveIt's default without robot_description_planning's
        arm.set_max_velocity_scaling_factor(0.3)
        arm.set_max_acceleration_scaling_factor(0.7)
        scaling = (arm.get_max_velocity_scaling_factor(), arm.get_max_acceleration_scaling_factor())
        self.assertEqual(scaling, (0.3, 0.7))

    def test_action_client_keeps_the_first_status_and_feedback_of_a_goal(self):
        # actionlib's own client drops them and logs an error: the race this client fixes.
        errors, active, feedback = send_with_fast_reply(
            actionlib.SimpleActionClient("race_stock", GripperCommandAction)
        )
        self.assertTrue(errors)
        self.assertEqual((active, feedback), ([], []))

        errors, active, feedback = send_with_fast_reply(ActionClient("race_fixed", GripperCommandAction))
        self.assertEqual(errors, [])
        self.assertEqual(active, [True])
        self.assertEqual([f.position for f in feedback], [0.01])

    def test_gripper_command_without_a_result_is_canceled_after_result_timeout(self):
        for name in ("robot_description", "robot_description_semantic"):
            rospy.set_param(f"/stuck/{name}", rospy.get_param(f"/{name}"))
        canceled = threading.Event()

        def never_finish(_goal):
            while not server.is_preempt_requested() and not rospy.is_shutdown():
                rospy.rostime.wallsleep(0.01)
            canceled.set()
            server.set_preempted()

        server = actionlib.SimpleActionServer(
            "/stuck/gripper_controller/gripper_cmd", GripperCommandAction, never_finish, auto_start=False
        )
        server.start()
        gripper = Gripper(ns="/stuck", wait_for_servers=60.0, result_timeout=0.5)
        with self.assertRaisesRegex(SixdofCommanderError, r"gripper command to 0: no result within 0.5 s .* canceled"):
            gripper.close()
        self.assertTrue(canceled.wait(10.0), "the server never saw the cancel")
        with self.assertRaisesRegex(SixdofCommanderError, "result_timeout must be a finite number of seconds >= 0"):
            Gripper(ns="/stuck", result_timeout=-1.0)

    def test_joint_state_monitor_reads_positions_and_names_missing_joints(self):
        monitor = JointStateMonitor("joint_states")
        publisher = rospy.Publisher("joint_states", JointState, queue_size=1, latch=True)
        publisher.publish(JointState(name=["joint1", "joint2"], position=[0.25, -0.5]))
        self.assertEqual(monitor.positions(["joint2", "joint1"], timeout=10.0), {"joint2": -0.5, "joint1": 0.25})
        with self.assertRaisesRegex(SixdofCommanderError, r"no position of \['joint9'\] received on '/joint_states'"):
            monitor.positions(["joint1", "joint9"], timeout=0.2)
        state = monitor.joint_state()
        self.assertEqual(dict(zip(state.name, state.position, strict=True)), {"joint1": 0.25, "joint2": -0.5})

    def test_joint_state_monitor_waits_for_a_state_stamped_after_a_time(self):
        monitor = JointStateMonitor("stamped_joint_states")
        publisher = rospy.Publisher("stamped_joint_states", JointState, queue_size=1, latch=True)
        self.assertFalse(monitor.wait_newer(0.0, timeout=0.1))  # nothing received yet
        message = JointState(name=["joint1"], position=[0.25])
        message.header.stamp = rospy.Time(5.0)
        publisher.publish(message)
        self.assertTrue(monitor.wait_newer(5.0, timeout=10.0))
        self.assertEqual(monitor.stamp, 5.0)
        self.assertFalse(monitor.wait_newer(5.5, timeout=0.2))  # older than asked: times out
        message.header.stamp = rospy.Time(6.0)
        threading.Timer(0.1, publisher.publish, (message,)).start()
        self.assertTrue(monitor.wait_newer(5.5, timeout=10.0))

    def test_error_reports_are_matched_by_node_and_interface_in_order(self):
        publisher = rospy.Publisher("move_group/error_reports", ErrorReport, queue_size=10)
        reports = ErrorReports()  # waits for the connection (its side of it)
        deadline = time.monotonic() + 10.0
        while publisher.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        self.assertEqual(publisher.get_num_connections(), 1)
        me = rospy.get_name()

        def report(caller, interface, message, val=MoveItErrorCodes.FAILURE):
            code = MoveItErrorCodes(val=val)
            publisher.publish(ErrorReport(caller_id=caller, interface=interface, message=message, error_code=code))

        report("/someone_else", "/compute_ik", "not mine")
        report(me, "/compute_ik", "first", MoveItErrorCodes.NO_IK_SOLUTION)
        report(me, "/plan_kinematic_path", "a plan's")
        report(me, "/compute_ik", "second")
        self.assertEqual(reports.take("compute_ik", timeout=10.0).message, "first")
        self.assertEqual(reports.take("/compute_ik", timeout=10.0).message, "second")
        self.assertIsNone(reports.take("compute_ik", timeout=0.2))
        # The answer's code wins; the report's words come with it.
        failure = reports.failure("plan_kinematic_path", MoveItErrorCodes.PLANNING_FAILED)
        self.assertEqual(str(failure), "PLANNING_FAILED (-1): a plan's")
        # No report: the code's name alone (after the wait); an answer without a code takes FAILURE.
        self.assertEqual(str(reports.failure("compute_fk", 0)), "FAILURE (99999)")
        # Reports nobody took are dropped before the next call to that interface.
        report(me, "/compute_fk", "stale")
        report(me, "/compute_ik", "marker")  # one connection keeps the order: once it is here, so is the stale one
        self.assertEqual(reports.take("compute_ik", timeout=10.0).message, "marker")
        reports.forget("compute_fk")
        self.assertIsNone(reports.take("compute_fk", timeout=0.2))
        # A topic's refusals go to its listener.
        heard = []
        reports.listen("planning_scene", heard.append)
        report(me, "/planning_scene", "object 'x': planes are not supported", MoveItErrorCodes.INVALID_OBJECT_NAME)
        deadline = time.monotonic() + 10.0
        while not heard and time.monotonic() < deadline:
            time.sleep(0.01)
        self.assertEqual([str(e) for e in heard], ["INVALID_OBJECT_NAME (-19): object 'x': planes are not supported"])


if __name__ == "__main__":
    rospy.init_node("commander_without_servers")
    rostest.rosrun("sixdof_scripts", "commander_without_servers", CommanderWithoutServers)
