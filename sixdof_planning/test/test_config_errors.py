#!/usr/bin/env python3
"""rostest: move_group refuses to start on bad configuration, with a message naming the parameter."""

import signal
import subprocess
import sys
import unittest

import rospy
import rostest
import yaml
from geometry_msgs.msg import Pose, Quaternion
from moveit_msgs.msg import CollisionObject, MoveItErrorCodes, PlanningScene, RobotState
from moveit_msgs.srv import (
    ApplyPlanningScene,
    GetPositionFK,
    GetStateValidity,
    GetStateValidityResponse,
)
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive

PKG = "sixdof_planning"


class ConfigErrorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_config_errors")
        # A complete, valid configuration loaded by the .test file under /good.
        cls.good = {
            "robot_description": rospy.get_param("/good/robot_description"),
            "robot_description_semantic": rospy.get_param("/good/robot_description_semantic"),
            "robot_description_kinematics": rospy.get_param("/good/robot_description_kinematics"),
            "robot_description_planning": rospy.get_param("/good/robot_description_planning"),
            "controller_list": rospy.get_param("/good/controller_list"),
        }
        cls.count = 0

    def namespace(self, params: dict) -> str:
        """A fresh namespace holding `params`, for one move_group."""
        ConfigErrorsTest.count += 1
        ns = f"/ns{self.count}"
        for key, value in params.items():
            rospy.set_param(f"{ns}/{key}", value)
        return ns

    def start(self, params: dict) -> subprocess.CompletedProcess:
        """Runs move_group in a fresh namespace holding `params`; it must exit by itself."""
        return subprocess.run(
            ["rosrun", PKG, "move_group", f"__ns:={self.namespace(params)}"],
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
        )

    def assert_refused(self, params: dict, *fragments: str) -> None:
        result = self.start(params)
        output = result.stdout + result.stderr
        self.assertEqual(result.returncode, 1, output)
        self.assertIn("bad configuration", output)
        for fragment in fragments:
            self.assertIn(fragment, output)

    def test_missing_semantic_description(self) -> None:
        params = dict(self.good)
        del params["robot_description_semantic"]
        self.assert_refused(params, "robot_description_semantic")

    def test_malformed_urdf(self) -> None:
        params = dict(self.good, robot_description="<robot name='x'><link name=")
        self.assert_refused(params, "robot_description")

    def test_unknown_ik_solver(self) -> None:
        kinematics = yaml.safe_load(yaml.safe_dump(self.good["robot_description_kinematics"]))
        kinematics["arm"]["kinematics_solver"] = "magic"
        self.assert_refused(dict(self.good, robot_description_kinematics=kinematics), "'magic'", "arm")

    def test_kinematics_for_unknown_group(self) -> None:
        kinematics = yaml.safe_load(yaml.safe_dump(self.good["robot_description_kinematics"]))
        kinematics["leg"] = dict(kinematics["arm"])
        self.assert_refused(dict(self.good, robot_description_kinematics=kinematics), "'leg'")

    def test_missing_acceleration_limit(self) -> None:
        planning = yaml.safe_load(yaml.safe_dump(self.good["robot_description_planning"]))
        planning["joint_limits"]["joint3"]["has_acceleration_limits"] = False
        self.assert_refused(dict(self.good, robot_description_planning=planning), "joint3", "acceleration")

    def test_missing_controller_list(self) -> None:
        params = dict(self.good)
        del params["controller_list"]
        self.assert_refused(params, "controller_list")

    def test_controller_with_unknown_joint(self) -> None:
        controllers = yaml.safe_load(yaml.safe_dump(self.good["controller_list"]))
        controllers[0]["joints"].append("joint9")
        self.assert_refused(dict(self.good, controller_list=controllers), "'joint9'", "arm_controller")

    def test_joint_in_two_controllers(self) -> None:
        controllers = yaml.safe_load(yaml.safe_dump(self.good["controller_list"]))
        controllers[1]["joints"].append("joint1")
        self.assert_refused(dict(self.good, controller_list=controllers), "'joint1'", "more than one controller")

    def test_negative_planning_time(self) -> None:
        result = self.start(dict(self.good, **{"move_group/default_planning_time": -1.0}))
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("default_planning_time", result.stdout + result.stderr)

    def test_planning_resolution_and_simplification_flags(self) -> None:
        # A plain loop, not subTest: rosunit drops failed subTests from its report.
        for value, fragment in ((0.0, "must be > 0"), (1.5, "must be <= 1"), ("fine", "is not a number")):
            self.assert_refused(
                dict(self.good, **{"move_group/longest_valid_segment_fraction": value}),
                "longest_valid_segment_fraction",
                fragment,
            )
        self.assert_refused(
            dict(self.good, **{"move_group/simplify_solutions": "yes"}), "simplify_solutions", "is not a bool"
        )
        for value, fragment in ((0.0, "must be > 0"), ("often", "is not a number")):
            self.assert_refused(
                dict(self.good, **{"move_group/trajectory_sample_period": value}), "trajectory_sample_period", fragment
            )

    def test_bad_occupancy_map_sensors(self) -> None:
        """The occupancy map monitor's parameters (sensor_manager.launch.xml, sensors_3d.yaml)."""
        sensor = {
            "sensor_plugin": "occupancy_map_monitor/PointCloudOctomapUpdater",
            "point_cloud_topic": "/cam/depth/points",
        }
        cases = (
            ({"octomap_resolution": -0.01}, ("move_group/octomap_resolution", "must be > 0")),
            ({"max_range": "far"}, ("move_group/max_range", "is not a number")),
            ({"sensors": {"a": sensor}}, ("move_group/sensors", "must be a list")),
            (
                {"sensors": [dict(sensor, sensor_plugin="occupancy_map_monitor/DepthImageOctomapUpdater")]},
                ("sensors[0]/sensor_plugin", "'occupancy_map_monitor/DepthImageOctomapUpdater' is not supported"),
            ),
            ({"sensors": [{"point_cloud_topic": "/cam"}]}, ("missing parameter", "sensors[0]/sensor_plugin")),
            (
                {"sensors": [sensor, {"sensor_plugin": sensor["sensor_plugin"]}]},
                ("missing parameter", "sensors[1]/point_cloud_topic"),
            ),
            ({"sensors": [dict(sensor, padding_offset=-0.1)]}, ("sensors[0]/padding_offset", "must be >= 0")),
            ({"sensors": [dict(sensor, point_subsample=1.5)]}, ("sensors[0]/point_subsample", "integer")),
            ({"sensors": [dict(sensor, max_rang=2.0)]}, ("unknown parameter", "sensors[0]/max_rang")),
        )
        # A plain loop, not subTest: rosunit drops failed subTests from its report.
        for params, fragments in cases:
            private = {f"move_group/{key}": value for key, value in params.items()}
            self.assert_refused(dict(self.good, **private), *fragments)

    def test_default_robot_padding_grows_the_links(self) -> None:
        """A 2 cm box 3 cm beyond the tool is clear of the arm, unless every link is padded by 5 cm."""
        answers = {}
        for padding in (0.0, 0.05):
            planning = yaml.safe_load(yaml.safe_dump(self.good["robot_description_planning"]))
            planning["default_robot_padding"] = padding
            ns = self.namespace(dict(self.good, robot_description_planning=planning))
            node = subprocess.Popen(
                ["rosrun", PKG, "move_group", f"__ns:={ns}"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
            )
            try:
                answers[padding] = self.validity_near_the_tool(ns)
            finally:
                node.send_signal(signal.SIGINT)
                node.wait(timeout=30)
        clear, padded = answers[0.0], answers[0.05]
        self.assertTrue(clear.valid, [(c.contact_body_1, c.contact_body_2) for c in clear.contacts])
        self.assertFalse(padded.valid)
        self.assertIn("probe", {name for c in padded.contacts for name in (c.contact_body_1, c.contact_body_2)})
        # Invalid start-up values are refused like the others.
        planning = yaml.safe_load(yaml.safe_dump(self.good["robot_description_planning"]))
        planning["default_robot_padding"] = -0.01
        self.assert_refused(dict(self.good, robot_description_planning=planning), "default_robot_padding", ">= 0")

    def validity_near_the_tool(self, ns: str) -> GetStateValidityResponse:
        """check_state_validity of the all-zero arm with a 2 cm box 3 cm beyond the tcp along its z axis."""
        rospy.wait_for_service(f"{ns}/check_state_validity", timeout=60)
        joints = JointState(name=[f"joint{i}" for i in range(1, 7)] + ["finger1_joint", "finger2_joint"])
        joints.position = [0.0] * 6 + [0.02, 0.02]
        state = RobotState(joint_state=joints)
        publisher = rospy.Publisher(f"{ns}/joint_states", JointState, queue_size=1, latch=True)
        publisher.publish(joints)
        fk = rospy.ServiceProxy(f"{ns}/compute_fk", GetPositionFK)(fk_link_names=["tcp"], robot_state=state)
        self.assertEqual(fk.error_code.val, MoveItErrorCodes.SUCCESS)
        tcp = fk.pose_stamped[0].pose
        q = tcp.orientation
        axis = Rotation.from_quat([q.x, q.y, q.z, q.w]).as_matrix()[:, 2]  # the tcp's z axis
        probe = CollisionObject(id="probe", operation=CollisionObject.ADD)
        probe.header.frame_id = fk.pose_stamped[0].header.frame_id
        probe.pose.position.x, probe.pose.position.y, probe.pose.position.z = (
            p + 0.03 * a for p, a in zip((tcp.position.x, tcp.position.y, tcp.position.z), axis, strict=True)
        )
        probe.pose.orientation.w = 1.0
        probe.primitives = [SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.02, 0.02, 0.02])]
        probe.primitive_poses = [Pose(orientation=Quaternion(w=1.0))]
        scene = PlanningScene(is_diff=True)
        scene.world.collision_objects = [probe]
        applied = rospy.ServiceProxy(f"{ns}/apply_planning_scene", ApplyPlanningScene)(scene=scene)
        self.assertTrue(applied.success)
        return rospy.ServiceProxy(f"{ns}/check_state_validity", GetStateValidity)(robot_state=state, group_name="arm")


if __name__ == "__main__":
    rostest.rosrun(PKG, "test_config_errors", ConfigErrorsTest, sys.argv)
