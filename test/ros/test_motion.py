#!/usr/bin/env python3
"""End-to-end motion through the whole headless stack (demo.launch headless:=true): poses reached by the paper's
moveto_xyzrpy measured from tf, every named pose and gripper state, a pose outside the workspace failing cleanly,
and the simulator's objects mirrored into the planning scene."""

import math
import sys
import unittest

import numpy as np
import rospy
import rostest
from e2e import (
    TfPoses,
    assert_scene_mirrors_simulator,
    case,
    settled_joint_state,
    wait_for_stack,
)
from moveit_msgs.msg import MoveItErrorCodes, RobotState
from moveit_msgs.srv import GetPositionFK
from scipy.spatial.transform import Rotation
from sixdof_commander import ArmDriver, MoveGroup, rad

# Pose goals for moveto_xyzrpy: link6 in these named states of the arm (compute_fk). The paper's own two poses are
# asserted in sixdof_description's test_urdf.py.
GOAL_STATES = ("home pose", "place pose")


class EndToEndMotion(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_motion")
        wait_for_stack()
        cls.driver = ArmDriver(wait_for_servers=60.0)
        cls.tf = TfPoses()

    def settled_positions(self) -> dict:
        msg = settled_joint_state()
        return dict(zip(msg.name, msg.position, strict=True)), msg.header.stamp

    def named_pose(self, name: str) -> tuple[list, Rotation]:
        """link6's position and orientation in the arm's named state `name` (move_group's compute_fk)."""
        values = self.driver.arm.get_named_target_values(name)
        state = RobotState(is_diff=True)
        state.joint_state.name, state.joint_state.position = list(values), list(values.values())
        response = rospy.ServiceProxy("compute_fk", GetPositionFK)(fk_link_names=["link6"], robot_state=state)
        self.assertEqual(response.error_code.val, MoveItErrorCodes.SUCCESS, f"compute_fk of '{name}'")
        p, q = response.pose_stamped[0].pose.position, response.pose_stamped[0].pose.orientation
        return [p.x, p.y, p.z], Rotation.from_quat([q.x, q.y, q.z, q.w])

    def test_poses_reached_within_1mm_and_half_a_degree(self):
        for name in GOAL_STATES:
            with case(pose=name):
                xyz, goal = self.named_pose(name)
                rpy = list(goal.as_euler("xyz"))
                self.assertTrue(self.driver.moveto_xyzrpy(xyz + rpy), self.driver.last_failure)
                _, stamp = self.settled_positions()
                position, rotation = self.tf.pose("link6", stamp)
                error = np.linalg.norm(position - np.array(xyz))
                angle = math.degrees((rotation.inv() * goal).magnitude())
                rospy.loginfo("%s: position error %.2f mm, orientation error %.3f deg", name, error * 1e3, angle)
                self.assertLess(error, 0.001)
                self.assertLess(angle, 0.5)

    def test_every_named_pose_and_gripper_state_is_reachable(self):
        for group_name, tolerance in (("arm", 0.005), ("gripper", 0.001)):
            group = MoveGroup(group_name, wait_for_servers=60.0)
            names = group.get_named_targets()
            self.assertTrue(names, f"group '{group_name}' has no named states")
            for name in names:
                with case(group=group_name, state=name):
                    group.set_named_target(name)
                    self.assertTrue(group.go(wait=True), f"'{name}': {group.last_error.message}")
                    positions, _ = self.settled_positions()
                    for joint, value in group.get_named_target_values(name).items():
                        self.assertAlmostEqual(positions[joint], value, delta=tolerance, msg=f"'{name}' {joint}")
        # The gripper action too: open and close with nothing between the fingers reach their positions, within
        # the tolerance at which the action reports reached_goal (gripper_action_controller's goal_tolerance).
        # (Closed, the pads touch each other: the simulator's contacts act 1 mm outside each pad, so they stop
        # about 2 mm short of 0, inside that tolerance.)
        goal_tolerance = rospy.get_param("gripper_controller/gripper_cmd/goal_tolerance", 0.002)
        gripper = self.driver.gripper
        for command, target in ((gripper.close, gripper.close_position), (gripper.open, gripper.open_position)):
            result = command()
            self.assertTrue(result.reached_goal)
            self.assertAlmostEqual(result.position, target, delta=goal_tolerance)

    def test_pose_outside_the_workspace_fails_cleanly_and_the_next_command_works(self):
        arm = self.driver.arm
        self.assertTrue(self.driver.moveto_named("home pose"), self.driver.last_failure)
        before, _ = self.settled_positions()
        # 2 m away: no arm configuration reaches it.
        self.assertFalse(self.driver.moveto_xyzrpy([2.0, 0.0, 0.3] + rad([180.0, 0.0, 0.0])))
        self.assertNotEqual(arm.last_error.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(arm.last_error.message, "the failure carries a message")
        after, _ = self.settled_positions()
        for joint in arm.get_active_joints():
            self.assertAlmostEqual(after[joint], before[joint], delta=0.005, msg=f"{joint} moved on a failed goal")
        xyz, goal = self.named_pose("home pose")
        self.assertTrue(self.driver.moveto_xyzrpy(xyz + list(goal.as_euler("xyz"))), self.driver.last_failure)

    def test_simulator_objects_are_mirrored_into_the_planning_scene(self):
        assert_scene_mirrors_simulator(self, rospy.get_param("scene_mirror/support_clearance", 0.002))


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_motion", EndToEndMotion, sys.argv)
