#!/usr/bin/env python3
"""pack_objects.py fills the 2x2 box of pack_world.yaml with objects picked from the running belt (exit 0, every
object upright in its slot), and refuses a box the world does not have (exit 2, one line). With whichever tool the
stack has: pack_objects.test (two-finger gripper), pack_objects_suction.test (suction cup)."""

import subprocess
import sys
import unittest

import rospy
import rostest
from e2e import wait_for_stack


def pack(*args: str, timeout: float) -> subprocess.CompletedProcess:
    return subprocess.run(
        ["rosrun", "sixdof_scripts", "pack_objects.py", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


class PackObjects(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_pack_objects")
        wait_for_stack("belt")

    def test_1_unknown_box(self):
        result = pack("--box", "crate", timeout=120)
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        self.assertIn("has no box (bin) 'crate'", result.stderr)

    def test_2_fills_a_2x2_box(self):
        result = pack("--box", "box", "--pattern", "2x2", "--timeout", "240", timeout=500)
        print(result.stdout, result.stderr, file=sys.stderr)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("packed 4/4", result.stdout)


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_pack_objects", PackObjects)
