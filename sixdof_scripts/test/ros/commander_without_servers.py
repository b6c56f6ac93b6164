#!/usr/bin/env python3
"""rostest: the commander's errors when its servers or parameters are missing, and joint_states reading."""

import unittest

import rospy
import rostest
from sensor_msgs.msg import JointState
from sixdof_commander import ArmDriver, Gripper, MoveGroup, PlanningScene, SixdofCommanderError
from sixdof_commander._ros import JointStateMonitor


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
        with self.assertRaisesRegex(SixdofCommanderError, "MoveGroup\\('arm'\\): action '/move_group'"):
            ArmDriver(wait_for_servers=0.2)

    def test_bad_arguments_fail_before_waiting(self):
        with self.assertRaisesRegex(SixdofCommanderError, "no group 'manipulator'"):
            MoveGroup("manipulator", wait_for_servers=0.2)
        with self.assertRaisesRegex(SixdofCommanderError, "wait_for_servers must be a finite number of seconds >= 0"):
            MoveGroup("arm", wait_for_servers=-1.0)
        with self.assertRaisesRegex(SixdofCommanderError, "parameter '/elsewhere/robot_description' is not set"):
            MoveGroup("arm", ns="/elsewhere", wait_for_servers=0.2)

    def test_joint_state_monitor_reads_positions_and_names_missing_joints(self):
        monitor = JointStateMonitor("joint_states")
        publisher = rospy.Publisher("joint_states", JointState, queue_size=1, latch=True)
        publisher.publish(JointState(name=["joint1", "joint2"], position=[0.25, -0.5]))
        self.assertEqual(monitor.positions(["joint2", "joint1"], timeout=10.0), {"joint2": -0.5, "joint1": 0.25})
        with self.assertRaisesRegex(SixdofCommanderError, r"no position of \['joint9'\] received on '/joint_states'"):
            monitor.positions(["joint1", "joint9"], timeout=0.2)
        state = monitor.joint_state()
        self.assertEqual(dict(zip(state.name, state.position, strict=True)), {"joint1": 0.25, "joint2": -0.5})


if __name__ == "__main__":
    rospy.init_node("commander_without_servers")
    rostest.rosrun("sixdof_scripts", "commander_without_servers", CommanderWithoutServers)
