#!/usr/bin/env python3
"""rostest: the gripper closes on the cube and stalls, the grasp fix attaches it, the cube follows a lift,
and opening the gripper releases it. Bad gripper goals are rejected."""

import math
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import FollowJointTrajectoryAction, GripperCommand, GripperCommandAction, GripperCommandGoal
from sim_test_util import (
    ARM_JOINTS,
    FINGER_JOINTS,
    GraspEventListener,
    JointStateListener,
    arm_geometry,
    at_rest,
    top_down_ik,
    trajectory_goal,
    wait_for_servers,
    wait_until,
)
from std_srvs.srv import Empty

from sixdof_msgs.msg import GraspEvent
from sixdof_msgs.srv import GetObjectState, SetObjectState
from sixdof_test_support.actions import wait_for_goal

CUBE = "red_cube"
TIMEOUT = 60.0  # s: simulated in wait_until, wall-clock in the other waits
LIFT = 0.10
GRASP_ABOVE_CENTRE = 0.01


class SimGraspTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_sim_grasp")
        cls.arm = actionlib.SimpleActionClient("arm_controller/follow_joint_trajectory", FollowJointTrajectoryAction)
        cls.gripper = actionlib.SimpleActionClient("gripper_controller/gripper_cmd", GripperCommandAction)
        wait_for_servers((cls.arm, cls.gripper), TIMEOUT)
        rospy.wait_for_service("sixdof_sim/reset_world", TIMEOUT)
        cls.reset_world = rospy.ServiceProxy("sixdof_sim/reset_world", Empty)
        cls.get_object = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
        cls.set_object = rospy.ServiceProxy("sixdof_sim/set_object_state", SetObjectState)
        cls.joints = JointStateListener()
        cls.grasps = GraspEventListener()
        cls.geometry = arm_geometry(rospy.get_param("robot_description"))

    def setUp(self) -> None:
        self.reset_world()

    def gripper_goal(self, position: float, max_effort: float = 0.0) -> tuple[int, object, str]:
        self.gripper.send_goal(GripperCommandGoal(command=GripperCommand(position=position, max_effort=max_effort)))
        self.assertTrue(wait_for_goal(self.gripper, TIMEOUT))
        return self.gripper.get_state(), self.gripper.get_result(), self.gripper.get_goal_status_text()

    def move_arm(self, joints: list[float], duration: float = 2.0) -> None:
        self.arm.send_goal(trajectory_goal(ARM_JOINTS, [(joints, duration)]))
        self.assertTrue(wait_for_goal(self.arm, TIMEOUT))
        self.assertEqual(self.arm.get_state(), GoalStatus.SUCCEEDED, self.arm.get_result().error_string)

    def cube(self):
        response = self.get_object(CUBE)
        self.assertTrue(response.success, response.status_message)
        return response

    def test_bad_gripper_goals_are_rejected(self) -> None:
        for position, effort, text in [(0.05, 0.0, "limits"), (0.02, -1.0, "negative"), (0.02, 1e6, "effort limit")]:
            state, _, status_text = self.gripper_goal(position, effort)
            self.assertEqual(state, GoalStatus.REJECTED)
            self.assertIn(text, status_text)
        state, result, _ = self.gripper_goal(0.03)
        self.assertEqual(state, GoalStatus.SUCCEEDED)
        self.assertTrue(result.reached_goal)
        self.assertTrue(self.joints.wait_near(FINGER_JOINTS, [0.03, 0.03], 0.0025))

    def test_grasp_lift_release(self) -> None:
        state, result, _ = self.gripper_goal(0.04)
        self.assertEqual(state, GoalStatus.SUCCEEDED)
        self.assertTrue(result.reached_goal)

        # Top-down grasp at the cube's centre; the cube is turned to face the fingers.
        pose = self.cube().object.pose
        # The finger tips reach past the tcp: grasping above the cube's centre keeps them off the table.
        grasp_z = pose.position.z + GRASP_ABOVE_CENTRE
        grasp = top_down_ik(self.geometry, pose.position.x, pose.position.y, grasp_z)
        above = top_down_ik(self.geometry, pose.position.x, pose.position.y, grasp_z + LIFT)
        pose.orientation.x, pose.orientation.y = 0.0, 0.0
        pose.orientation.z, pose.orientation.w = math.sin(0.5 * grasp[0]), math.cos(0.5 * grasp[0])
        self.assertTrue(self.set_object(CUBE, pose, self.cube().twist).success)
        self.assertTrue(wait_until(lambda: at_rest(self.cube()), TIMEOUT), "the turned cube did not come to rest")
        self.move_arm(above)
        self.move_arm(grasp)

        state, result, text = self.gripper_goal(0.0)
        self.assertEqual(state, GoalStatus.SUCCEEDED, text)
        self.assertTrue(result.stalled)
        self.assertFalse(result.reached_goal)
        self.assertGreater(result.position, 0.015)  # held apart by the 4 cm cube
        self.assertTrue(self.grasps.wait_for(GraspEvent.ATTACHED, CUBE, 10.0), "no attach event")
        self.assertEqual(self.cube().attached_to, "link6")

        z_before = self.cube().object.pose.position.z
        self.move_arm(above)
        self.assertGreater(self.cube().object.pose.position.z, z_before + 0.8 * LIFT)

        state, result, text = self.gripper_goal(0.04)
        self.assertEqual(state, GoalStatus.SUCCEEDED, text)
        self.assertTrue(self.grasps.wait_for(GraspEvent.DETACHED, CUBE, 10.0), "no detach event")
        self.assertTrue(wait_until(lambda: at_rest(self.cube()), TIMEOUT), "the released cube did not come to rest")
        cube = self.cube()
        self.assertEqual(cube.attached_to, "")
        self.assertLess(cube.object.pose.position.z, z_before + 0.02)  # fell back onto the table


if __name__ == "__main__":
    rostest.rosrun("sixdof_sim", "test_sim_grasp", SimGraspTest)
