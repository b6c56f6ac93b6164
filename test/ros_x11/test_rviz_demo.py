#!/usr/bin/env python3
"""rviz of demo.launch on a virtual X display: its window appears, a screenshot shows the robot (its
orange links) and the simulator's red cube (object markers), and rviz logs no error."""

import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
from rosgraph_msgs.msg import Log

from sixdof_rviz.screenshots import channels, screenshot

# rviz prints these when the optional package media_export is missing; they are harmless.
HARMLESS = ("no such package media_export", "error while executing command")
# Hang guard only: rviz under Mesa llvmpipe shows its first frame within seconds when healthy.
WAIT = 120.0


def robot_mask(image: np.ndarray) -> np.ndarray:
    """The arm's orange material (0.93, 0.45, 0.10) under any shading: red high, green about half of red,
    blue low. The brown table (0.55, 0.40, 0.25) has too much blue, the red cube too little green."""
    r, g, b = channels(image)
    return (r > 90) & (g * 10 > r * 3) & (g * 10 < r * 7) & (b * 10 < r * 3)


def cube_mask(image: np.ndarray) -> np.ndarray:
    """The red cube (0.9, 0.1, 0.1)."""
    r, g, b = channels(image)
    return (r > 90) & (g * 4 < r) & (b * 4 < r)


def rviz_window_shown() -> bool:
    tree = subprocess.run(["xwininfo", "-root", "-tree"], capture_output=True, text=True).stdout
    return "rviz" in tree.lower()


class RvizDemo(unittest.TestCase):
    def test_screenshot_shows_the_robot_and_the_cube(self):
        errors = []
        lock = threading.Lock()

        def on_log(msg: Log) -> None:
            if msg.level >= Log.ERROR and "rviz" in msg.name and not any(h in msg.msg for h in HARMLESS):
                with lock:
                    errors.append(msg.msg)

        rospy.Subscriber("/rosout", Log, on_log, queue_size=100)
        deadline = time.monotonic() + WAIT
        while not rviz_window_shown():
            self.assertLess(time.monotonic(), deadline, "no rviz window on the display")
            time.sleep(0.5)
        robot = cube = 0
        with tempfile.TemporaryDirectory() as tmp:
            # rviz draws the robot once tf arrives and the cube once the markers do: take shots until both show.
            while time.monotonic() < deadline:
                # The 3D view only: the Displays panel on the left has small orange and red icons.
                image = screenshot(save_as=f"{tmp}/shot.png")[:, 400:]
                robot, cube = int(robot_mask(image).sum()), int(cube_mask(image).sum())
                if robot > 2000 and cube > 50:
                    break
                time.sleep(1.0)
        rospy.loginfo("screenshot: %d robot pixels, %d cube pixels", robot, cube)
        self.assertGreater(robot, 2000, "the robot is not visible")
        self.assertGreater(cube, 50, "the red cube is not visible")
        with lock:
            self.assertEqual(errors, [])


if __name__ == "__main__":
    rospy.init_node("test_rviz_demo")
    rostest.rosrun("sixdof_tests", "test_rviz_demo", RvizDemo, sys.argv)
