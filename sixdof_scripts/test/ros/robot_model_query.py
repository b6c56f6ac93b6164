#!/usr/bin/env python3
"""rostest: the commander's robot model comes from move_group's get_robot_model and agrees, on the shared
joint-kinds fixture, with what sixdof_core, sixdof_sim and sixdof_rviz test (test_joint_kinds): the link and
joint order, a continuous joint unbounded with the nominal -pi..pi, prismatic limits, the mimic finger, the fixed
mount link and the link without geometry or inertia, groups, named states and the end effector; the links'
collision shapes when asked for (box, cylinder and sphere, posed in the link frame; links without geometry have
none); and that the Jacobian computed from that model (get_jacobian_matrix) is the derivative of move_group's
forward kinematics; and that retime_trajectory's iterative parabolic parameterization and the random joint values (the
core's, through its bindings) keep to the joint limits move_group reads."""

import math
import unittest

import numpy as np
import rospy
import rostest
from moveit_commander import RobotCommander
from moveit_msgs.msg import RobotState, RobotTrajectory
from moveit_msgs.srv import GetPositionFK
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import MoveGroup, SixdofCommanderError
from sixdof_commander._ros import query_robot_model
from sixdof_commander.robot_model import resolve_group
from sixdof_commander.transforms import matrix_from_pose
from trajectory_msgs.msg import JointTrajectoryPoint

LINKS = ["mount", "base_link", "turntable", "carriage", "head", "sensor_frame", "left_finger", "right_finger"]


class RobotModelQuery(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.urdf, cls.srdf = query_robot_model("", timeout=60.0)

    def test_order_is_the_core_models(self):
        self.assertEqual(self.urdf.root_link, "mount")
        self.assertEqual(list(self.urdf.link_order), LINKS)
        self.assertEqual([joint.child for joint in self.urdf.joints.values()], LINKS[1:])
        active = [joint.name for joint in self.urdf.joints.values() if joint.is_active]
        self.assertEqual(active, ["spin", "lift", "tilt", "finger_left"])
        robot = RobotCommander()
        self.assertEqual(robot.get_link_names(), LINKS)
        self.assertEqual(robot.get_active_joint_names(), ["spin", "lift", "tilt", "finger_left"])
        self.assertEqual(robot.get_joint("spin").bounds(), [-math.pi, math.pi])

    def test_joint_kinds_and_limits(self):
        spin = self.urdf.joints["spin"]
        self.assertEqual(spin.type, "continuous")
        self.assertFalse(spin.bounded)
        self.assertEqual((spin.lower, spin.upper), (-math.pi, math.pi))
        self.assertAlmostEqual(spin.velocity, 2.0)
        lift = self.urdf.joints["lift"]
        self.assertEqual(lift.type, "prismatic")
        self.assertTrue(lift.bounded)
        self.assertEqual((lift.lower, lift.upper), (0.0, 0.3))
        right = self.urdf.joints["finger_right"]
        self.assertEqual(right.mimic, "finger_left")
        self.assertEqual((right.mimic_multiplier, right.mimic_offset), (1.0, 0.0))
        self.assertFalse(right.is_active)
        self.assertEqual(self.urdf.joints["mount_joint"].type, "fixed")
        self.assertEqual(self.urdf.joints["sensor_joint"].type, "fixed")
        # The lift's origin as the URDF gives it, in the turntable frame.
        np.testing.assert_allclose(self.urdf.joints["lift"].origin[:3, 3], [0.1, 0.0, 0.05], atol=1e-12)

    def test_jacobian_is_the_derivative_of_move_groups_forward_kinematics(self):
        # Continuous, prismatic and revolute columns, at a point off the tip link's origin.
        arm = MoveGroup("arm", wait_for_servers=60.0)
        fk = rospy.ServiceProxy("compute_fk", GetPositionFK)
        point = np.array([0.1, 0.02, -0.03, 1.0])
        names = arm.get_active_joints()

        def pose(values):
            # No joint_states here: the state names every variable (the gripper's at 0).
            state = RobotState(is_diff=False)
            state.joint_state.name, state.joint_state.position = [*names, "finger_left"], [*values, 0.0]
            response = fk(fk_link_names=["head"], robot_state=state)
            self.assertEqual(response.error_code.val, response.error_code.SUCCESS)
            return matrix_from_pose(response.pose_stamped[0].pose)

        step = 1e-6
        for values in ([0.0, 0.1, 0.0], [2.5, 0.27, -1.2], [-3.0, 0.05, 1.4]):
            jacobian = arm.get_jacobian_matrix(values, list(point[:3]))
            self.assertEqual(jacobian.shape, (6, 3))
            base = pose(values)
            for column in range(3):
                shifted = list(values)
                shifted[column] += step
                moved = pose(shifted)
                np.testing.assert_allclose(jacobian[:3, column], (moved @ point - base @ point)[:3] / step, atol=1e-5)
                spin = (moved[:3, :3] - base[:3, :3]) / step @ base[:3, :3].T
                np.testing.assert_allclose(jacobian[3:, column], [spin[2, 1], spin[0, 2], spin[1, 0]], atol=1e-5)

    def test_iterative_retiming_and_random_values_keep_to_the_limits(self):
        arm = MoveGroup("arm", wait_for_servers=60.0)
        names = arm.get_active_joints()
        limits = rospy.get_param("robot_description_planning/joint_limits")
        velocity = np.array([self.urdf.joints[name].velocity for name in names])
        acceleration = np.array([limits[name]["max_acceleration"] for name in names])
        path = np.array([[0.0, 0.1, 0.0], [0.5, 0.2, 0.3], [1.0, 0.25, -0.2], [1.2, 0.05, 0.0]])
        trajectory = RobotTrajectory()
        trajectory.joint_trajectory.joint_names = names
        trajectory.joint_trajectory.points = [JointTrajectoryPoint(positions=list(p)) for p in path]
        durations = {}
        for factor in (0.5, 1.0):
            points = arm.retime_trajectory(RobotState(), trajectory, factor, factor).joint_trajectory.points
            np.testing.assert_array_equal([p.positions for p in points], path)
            times = np.array([p.time_from_start.to_sec() for p in points])
            velocities = np.array([p.velocities for p in points])
            self.assertEqual(times[0], 0.0)
            self.assertTrue(np.all(np.diff(times) > 0.0))
            self.assertFalse(velocities[[0, -1]].any())
            steps = np.diff(times)[:, None]
            self.assertTrue(np.all(np.abs(np.diff(path, axis=0)) / steps <= velocity * factor * 1.0001))
            self.assertTrue(np.all(np.abs(np.diff(velocities, axis=0)) / steps <= acceleration * factor * 1.0001))
            durations[factor] = times[-1]
        self.assertGreater(durations[0.5], durations[1.0])
        with self.assertRaisesRegex(SixdofCommanderError, "unknown algorithm 'fast'"):
            arm.retime_trajectory(RobotState(), trajectory, algorithm="fast")
        for _ in range(20):
            for name, value in zip(names, arm.get_random_joint_values(), strict=True):
                joint = self.urdf.joints[name]
                self.assertTrue(joint.lower <= value <= joint.upper, (name, value))

    def test_collision_geometry_on_request(self):
        self.assertIsNone(self.urdf.collision)  # not asked for: the response stays small
        urdf, _ = query_robot_model("", timeout=60.0, collision_geometry=True)
        # The links with <collision>, in model order (mount and sensor_frame have none).
        with_geometry = ["base_link", "turntable", "carriage", "head", "left_finger", "right_finger"]
        self.assertEqual(list(urdf.collision), with_geometry)
        expected = {
            "base_link": (SolidPrimitive.BOX, [0.2, 0.2, 0.1], [0.0, 0.0, 0.05]),
            "turntable": (SolidPrimitive.CYLINDER, [0.05, 0.08], [0.0, 0.0, 0.025]),  # height, radius
            "carriage": (SolidPrimitive.BOX, [0.06, 0.06, 0.06], [0.0, 0.0, 0.0]),
            "head": (SolidPrimitive.SPHERE, [0.03], [0.05, 0.0, 0.0]),
        }
        for link, (kind, dimensions, position) in expected.items():
            geometry = urdf.collision[link]
            self.assertEqual(geometry.link_name, link)
            self.assertEqual(len(geometry.meshes), 0)
            self.assertEqual([p.type for p in geometry.primitives], [kind], link)
            np.testing.assert_allclose(geometry.primitives[0].dimensions, dimensions, atol=1e-12)
            pose = np.eye(4)
            pose[:3, 3] = position
            np.testing.assert_allclose(matrix_from_pose(geometry.primitive_poses[0]), pose, atol=1e-12)
        # The points bounding the head's sphere, in the head frame.
        points = urdf.collision_points("head")
        np.testing.assert_allclose(points.min(axis=0), [0.02, -0.03, -0.03], atol=1e-12)
        np.testing.assert_allclose(points.max(axis=0), [0.08, 0.03, 0.03], atol=1e-12)
        self.assertEqual(urdf.collision_points("sensor_frame").shape, (0, 3))

    def test_groups_states_and_end_effector(self):
        arm = resolve_group(self.urdf, self.srdf, "arm")
        self.assertEqual(arm.joint_names, ["spin", "lift", "tilt"])
        self.assertEqual(arm.tip_link, "head")
        self.assertEqual(arm.end_effector_link, "head")
        self.assertEqual(arm.end_effector_group, "gripper")
        self.assertEqual(arm.named_states["home"], {"spin": 0.0, "lift": 0.1, "tilt": 0.0})
        gripper = resolve_group(self.urdf, self.srdf, "gripper")
        self.assertEqual(gripper.joint_names, ["finger_left"])
        self.assertEqual([joint.name for joint in gripper.all_joints], ["finger_left", "finger_right"])
        self.assertEqual(sorted(gripper.named_states), ["close", "open"])
        self.assertEqual(self.srdf.virtual_joint_parent, "world")


if __name__ == "__main__":
    rospy.init_node("robot_model_query")
    rostest.rosrun("sixdof_scripts", "robot_model_query", RobotModelQuery)
