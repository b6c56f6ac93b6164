#!/usr/bin/env python3
"""rostest: move_group refuses to start on bad configuration, with a message naming the parameter."""

import subprocess
import sys
import unittest

import rospy
import rostest
import yaml

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

    def start(self, params: dict) -> subprocess.CompletedProcess:
        """Runs move_group in a fresh namespace holding `params`; it must exit by itself."""
        ConfigErrorsTest.count += 1
        ns = f"/bad{self.count}"
        for key, value in params.items():
            rospy.set_param(f"{ns}/{key}", value)
        return subprocess.run(
            ["rosrun", PKG, "move_group", f"__ns:={ns}"],
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


if __name__ == "__main__":
    rostest.rosrun(PKG, "test_config_errors", ConfigErrorsTest, sys.argv)
