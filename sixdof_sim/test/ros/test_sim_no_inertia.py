#!/usr/bin/env python3
"""rostest: sixdof_sim's node started on a URDF whose moving link has no <inertial> exits with an error code and
one line naming that link and its joint (as Gazebo refuses such a model), instead of simulating a massless body."""

import subprocess
import unittest

import rospy
import rostest

# A base and one revolute joint moving 'swing', which has geometry but no <inertial>.
URDF = """<?xml version="1.0"?>
<robot name="no_inertia">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="swing">
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.02 0.02 0.2"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="swing"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
</robot>
"""
NAMESPACE = "/no_inertia"
# Outcome bound: the node reads one parameter and fails while building its world.
EXIT_TIMEOUT = 60.0


class SimNoInertia(unittest.TestCase):
    def test_moving_link_without_inertia_is_one_line_naming_it(self):
        rospy.set_param(f"{NAMESPACE}/robot_description", URDF)
        # What a generated config package's controllers.yaml gives the node.
        rospy.set_param(
            f"{NAMESPACE}/controller_list",
            [{"name": "arm_controller", "action_ns": "follow_joint_trajectory", "joints": ["hinge"]}],
        )
        run = subprocess.run(
            ["rosrun", "sixdof_sim", "sixdof_sim", f"__ns:={NAMESPACE}"],
            capture_output=True,
            text=True,
            timeout=EXIT_TIMEOUT,
        )
        self.assertNotEqual(run.returncode, 0, f"the simulator accepted a massless moving link:\n{run.stdout}")
        errors = [line for line in (run.stdout + run.stderr).splitlines() if "FATAL" in line or "ERROR" in line]
        self.assertEqual(len(errors), 1, f"expected one error line, got:\n{run.stdout}{run.stderr}")
        self.assertIn("link 'swing' cannot be simulated", errors[0])
        self.assertIn("joint 'hinge'", errors[0])


if __name__ == "__main__":
    rospy.init_node("sim_no_inertia")
    rostest.rosrun("sixdof_sim", "sim_no_inertia", SimNoInertia)
