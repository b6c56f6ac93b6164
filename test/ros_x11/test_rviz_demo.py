#!/usr/bin/env python3
"""rviz of demo.launch on a virtual X display: its window appears, a screenshot shows the robot (its
orange links) and the simulator's red cube (object markers), and rviz logs no error.

rviz on Mesa's software renderer under Xvfb dies now and then in its first frames (sixdof_rviz.rviz_process says
how). rviz_demo.test starts it with rviz_respawn; the test allows restarts until rviz shows the robot (rviz_process's
STARTS starts at most) and logs each, and the rviz that shows it must stay up for STAY_UP seconds after."""

import sys
import threading
import time
import unittest
from pathlib import Path
from xmlrpc.client import ServerProxy

import numpy as np
import rosgraph
import rosnode
import rospkg
import rospy
import rostest
from rosgraph_msgs.msg import Log

from sixdof_rviz.rviz_process import STARTS, STAY_UP, main_window
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


def rviz_pid() -> int | None:
    """The process id of the node /rviz; None while it is not registered or does not answer."""
    try:
        uri = rosnode.get_api_uri(rosgraph.Master("/test_rviz_demo"), "/rviz", skip_cache=True)
        code, _, pid = ServerProxy(uri).getPid("/test_rviz_demo") if uri else (0, "", 0)
    except (OSError, rosgraph.MasterException, rosnode.ROSNodeIOException):
        return None
    return pid if code == 1 else None


class RvizProcesses(threading.Thread):
    """The process ids /rviz has had, polled twice a second while the test runs."""

    def __init__(self) -> None:
        super().__init__(daemon=True)
        self.pids: list[int] = []
        self.stopped = threading.Event()

    def run(self) -> None:
        while not self.stopped.wait(0.5):
            pid = rviz_pid()
            if pid is not None and pid not in self.pids:
                self.pids.append(pid)
                if len(self.pids) > 1:
                    rospy.logwarn("rviz died and was started again (pids %s)", self.pids)


class RvizDemo(unittest.TestCase):
    def test_screenshot_shows_the_robot_and_the_cube(self):
        errors = []
        lock = threading.Lock()

        def on_log(msg: Log) -> None:
            if msg.level >= Log.ERROR and "rviz" in msg.name and not any(h in msg.msg for h in HARMLESS):
                with lock:
                    errors.append(msg.msg)

        rospy.Subscriber("/rosout", Log, on_log, queue_size=100)
        processes = RvizProcesses()
        processes.start()
        deadline = time.monotonic() + WAIT
        while main_window() is None:
            self.assertLess(time.monotonic(), deadline, "no rviz window on the display")
            time.sleep(0.5)
        robot = cube = 0
        # The last screenshot stays in the run's log directory (beside rviz's log) for a person to look at.
        shot = Path(rospkg.get_log_dir()) / rospy.get_param("/run_id") / "rviz_demo.png"
        # rviz draws the robot once tf arrives and the cube once the markers do: take shots until both show.
        while time.monotonic() < deadline:
            # The 3D view only: the Displays panel on the left has small orange and red icons.
            image = screenshot(save_as=str(shot))[:, 400:]
            robot, cube = int(robot_mask(image).sum()), int(cube_mask(image).sum())
            if robot > 2000 and cube > 50:
                break
            time.sleep(1.0)
        shown = robot > 2000 and cube > 50
        shown_by = list(processes.pids)
        if shown:
            time.sleep(STAY_UP)
        processes.stopped.set()
        processes.join()
        rospy.loginfo("screenshot %s: %d robot pixels, %d cube pixels", shot, robot, cube)
        deaths = len(processes.pids) - 1
        self.assertLessEqual(len(processes.pids), STARTS, f"rviz died {deaths} times: pids {processes.pids}")
        self.assertGreater(robot, 2000, f"the robot is not visible in {shot}")
        self.assertGreater(cube, 50, f"the red cube is not visible in {shot}")
        self.assertEqual(processes.pids, shown_by, f"rviz died after it showed the robot: pids {processes.pids}")
        with lock:
            self.assertEqual(errors, [])


if __name__ == "__main__":
    rospy.init_node("test_rviz_demo")
    rostest.rosrun("sixdof_tests", "test_rviz_demo", RvizDemo, sys.argv)
