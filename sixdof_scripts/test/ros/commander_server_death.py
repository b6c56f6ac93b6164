#!/usr/bin/env python3
"""rostest: go(), plan(), execute() and the gripper return (False with an error code, or SixdofCommanderError)
when the node serving them is killed mid-request, instead of waiting forever (issue 13, item 3); the kept
connection of a PersistentService is replaced when its server restarted, and a server's error answer is never
made again.

The server is a stand-in of our own (stand_in_move_group.py) that never answers, started per case and killed by
pid with SIGKILL once the request is in flight. Bounds are hang guards (the call returned at all), not speed."""

import os
import signal
import subprocess
import sys
import threading
import time
import unittest
from pathlib import Path

import rospy
import rostest
from moveit_msgs.msg import MoveItErrorCodes, RobotTrajectory
from moveit_msgs.srv import GetPositionFK, GetPositionIK
from sixdof_commander import Gripper, MoveGroup, SixdofCommanderError
from sixdof_commander._service import PersistentService, call_service
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.srv import GetRobotModel, GetRobotModelRequest

STAND_IN = Path(__file__).resolve().parent / "stand_in_move_group.py"
HANG_GUARD = 60.0


class StandIn:
    """The stand-in server process; kill() sends SIGKILL to its pid."""

    def __init__(self) -> None:
        if rospy.has_param("/stand_in"):
            rospy.delete_param("/stand_in")
        self.process = subprocess.Popen([sys.executable, str(STAND_IN)])

    def wait_for_request(self, name: str) -> None:
        deadline = time.monotonic() + HANG_GUARD
        while not rospy.get_param(f"/stand_in/received/{name}", False):
            assert time.monotonic() < deadline, f"the stand-in never received the {name} request"
            time.sleep(0.05)

    def kill(self) -> None:
        os.kill(self.process.pid, signal.SIGKILL)
        self.process.wait()


def in_thread(call):
    """Runs call() in a thread; returns (thread, outcome dict with 'value' or 'error')."""
    outcome = {}

    def run():
        try:
            outcome["value"] = call()
        except Exception as err:  # the test inspects it
            outcome["error"] = err

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread, outcome


class CommanderServerDeath(unittest.TestCase):
    def run_and_kill(self, make, call, request: str):
        stand_in = StandIn()
        try:
            client = make()
            thread, outcome = in_thread(lambda: call(client))
            stand_in.wait_for_request(request)
            stand_in.kill()
            thread.join(HANG_GUARD)
            self.assertFalse(thread.is_alive(), f"the call did not return within {HANG_GUARD} s of the kill")
            return client, outcome
        finally:
            if stand_in.process.poll() is None:
                stand_in.kill()

    def test_go_returns_false_naming_the_lost_server(self):
        def go(arm):
            arm.set_joint_value_target([0.0] * 6)
            return arm.go(wait=True)

        arm, outcome = self.run_and_kill(lambda: MoveGroup("arm", wait_for_servers=HANG_GUARD), go, "move_group")
        self.assertIs(outcome.get("value"), False, outcome)
        self.assertEqual(arm.last_error.val, MoveItErrorCodes.COMMUNICATION_FAILURE)
        self.assertIn("move_group", arm.last_error.message)
        self.assertIn("lost", arm.last_error.message)

    def test_execute_returns_false_naming_the_lost_server(self):
        trajectory = RobotTrajectory()
        trajectory.joint_trajectory.joint_names = [f"joint{i}" for i in range(1, 7)]
        trajectory.joint_trajectory.points.append(JointTrajectoryPoint(positions=[0.0] * 6))
        arm, outcome = self.run_and_kill(
            lambda: MoveGroup("arm", wait_for_servers=HANG_GUARD), lambda a: a.execute(trajectory), "execute_trajectory"
        )
        self.assertIs(outcome.get("value"), False, outcome)
        self.assertIn("execute_trajectory", arm.last_error.message)

    def test_plan_returns_false_with_a_communication_failure(self):
        def plan(arm):
            arm.set_joint_value_target([0.0] * 6)
            return arm.plan()

        arm, outcome = self.run_and_kill(
            lambda: MoveGroup("arm", wait_for_servers=HANG_GUARD), plan, "plan_kinematic_path"
        )
        success, trajectory, _, code = outcome["value"]
        self.assertFalse(success)
        self.assertEqual(code.val, MoveItErrorCodes.COMMUNICATION_FAILURE)
        self.assertEqual(arm.last_error.val, MoveItErrorCodes.COMMUNICATION_FAILURE)
        self.assertIn("plan_kinematic_path", arm.last_error.message)
        # The node is gone: the next call fails at once instead of waiting.
        success, _, _, code = arm.plan()
        self.assertFalse(success)
        self.assertEqual(code.val, MoveItErrorCodes.COMMUNICATION_FAILURE)

    def test_a_service_that_never_answers_is_given_up_after_its_timeout(self):
        stand_in = StandIn()
        try:
            rospy.wait_for_service("compute_fk", timeout=HANG_GUARD)
            proxy = rospy.ServiceProxy("compute_fk", GetPositionFK)
            with self.assertRaisesRegex(rospy.ROSException, "service '/compute_fk' gave no answer within 0.5 s"):
                call_service(proxy, GetPositionFK._request_class(), 0.5)
        finally:
            stand_in.kill()

    def test_a_kept_connection_that_stops_answering_is_given_up_after_its_timeout(self):
        stand_in = StandIn()
        try:
            rospy.wait_for_service("compute_ik", timeout=HANG_GUARD)
            service = PersistentService("compute_ik", GetPositionIK)
            request = GetPositionIK._request_class()
            call_service(service, request, HANG_GUARD)  # answered: the connection is kept
            for _ in range(2):  # on the kept connection, then on a new one
                with self.assertRaisesRegex(rospy.ROSException, "service '/compute_ik' gave no answer within 0.5 s"):
                    call_service(service, request, 0.5)
        finally:
            stand_in.kill()

    def test_a_kept_connection_is_replaced_after_the_server_restarted(self):
        # PersistentService keeps its connection between calls; a server that died and came back gets a new one.
        service = PersistentService("get_robot_model", GetRobotModel)
        request = GetRobotModelRequest()
        for _ in range(2):
            stand_in = StandIn()
            try:
                # rospy's wait connects to the registered server: a killed one's registration is not taken for it.
                rospy.wait_for_service("get_robot_model", timeout=HANG_GUARD)
                answers = [service(request) for _ in range(2)] + [call_service(service, request, HANG_GUARD)]
                self.assertTrue(all(a.error_code.val == MoveItErrorCodes.SUCCESS for a in answers))
                # Calls from two threads at once are both answered.
                threads = [in_thread(lambda: service(request)) for _ in range(2)]
                for thread, outcome in threads:
                    thread.join(HANG_GUARD)
                    self.assertEqual(outcome["value"].error_code.val, MoveItErrorCodes.SUCCESS, outcome)
            finally:
                stand_in.kill()

    def test_an_error_answer_is_not_made_again(self):
        # A server's error answer (TCPROS's ok byte 0) raises and is never made again, on a new connection or the kept
        # one, by either way of calling: a service with side effects runs once per call.
        handled = []
        refuse = [True]

        def handle(request):
            handled.append(request)
            if refuse[0]:
                raise rospy.ServiceException("refused on purpose")
            return GetPositionFK._response_class()

        server = rospy.Service("counting_fk", GetPositionFK, handle)
        try:
            service = PersistentService("counting_fk", GetPositionFK)
            request = GetPositionFK._request_class()
            calls = [lambda: service(request), lambda: call_service(service, request, HANG_GUARD)]
            for call in calls:  # on a new connection (the server refuses): not kept
                with self.assertRaisesRegex(rospy.ServiceException, "refused on purpose"):
                    call()
            self.assertEqual(len(handled), 2)
            refuse[0] = False
            service(request)  # answered: the connection is kept
            refuse[0] = True
            for call in calls + calls:  # on the kept connection
                with self.assertRaisesRegex(rospy.ServiceException, "refused on purpose"):
                    call()
            self.assertEqual(len(handled), 7)
            refuse[0] = False
            self.assertIsNotNone(call_service(service, request, HANG_GUARD))  # the connection outlived the errors
            self.assertEqual(len(handled), 8)
        finally:
            server.shutdown()

    def test_gripper_raises_naming_the_lost_server(self):
        _, outcome = self.run_and_kill(
            lambda: Gripper(wait_for_servers=HANG_GUARD, result_timeout=0.0),
            lambda g: g.close(),
            "gripper_controller/gripper_cmd",
        )
        self.assertIsInstance(outcome.get("error"), SixdofCommanderError, outcome)
        self.assertIn("action server was lost", str(outcome["error"]))


if __name__ == "__main__":
    rospy.init_node("commander_server_death")
    rostest.rosrun("sixdof_scripts", "commander_server_death", CommanderServerDeath)
