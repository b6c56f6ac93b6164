"""What the real-robot tests share (real_robot.py, real_launch.py): a launched real.launch, the Dynamixel servo
emulator as a child process, the driver's services, and a pick motion sequence without objects."""

from __future__ import annotations

import math
import subprocess
import time
from pathlib import Path

import numpy as np
import rospy
import yaml
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import FollowJointTrajectoryActionResult
from e2e import STARTUP_TIMEOUT
from generated import start, stop
from sixdof_commander import ArmDriver
from std_srvs.srv import SetBool, Trigger

# Bounds are outcomes (the error came, nothing hung), not speed claims.
FAULT_BOUND = 1.0  # s from a hardware fault or an e-stop to the driver's aborted goal (docs/real_robot.md)
MOTION_TIMEOUT = 120.0
# The dynamixel plugin's status packet timeout (s) against the emulator, and the loop's read_timeout twice that: the
# emulator is a Python process on the two cores the whole stack shares, and its answers can wait for the scheduler
# longer than the 20 ms a servo gets by default (a hardware fault). A servo that stops answering is still found
# within FAULT_BOUND.
EMULATOR_TIMEOUT = 0.1


def launch(args: list[str], log: Path) -> subprocess.Popen:
    """roslaunch ARGS in a process group of its own, its output into log."""
    return start(["roslaunch", *args], log)


class Emulator:
    """sixdof_control's Dynamixel Protocol 2.0 servo emulator on a pseudo-terminal, driven by its stdin commands."""

    def __init__(self, ids: list[int], lag: float = 0.05) -> None:
        self.process = subprocess.Popen(
            ["rosrun", "sixdof_control", "dynamixel_emulator", "--ids", *map(str, ids), "--lag", str(lag)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, start_new_session=True,
        )
        first = self.process.stdout.readline().strip()
        assert first.startswith("port "), f"the emulator did not start: {first!r}"
        self.port = first.removeprefix("port ")

    def driver_args(self, hardware: Path, scratch: Path) -> list[str]:
        """real.launch's arguments for the dynamixel plugin on this emulator: the hardware.yaml `hardware` copied into
        the folder `scratch` with the dynamixel block's timeout EMULATOR_TIMEOUT and read_timeout twice it."""
        config = yaml.safe_load(hardware.read_text())
        config["dynamixel"]["timeout"] = EMULATOR_TIMEOUT
        config["read_timeout"] = 2.0 * EMULATOR_TIMEOUT
        copy = scratch / "hardware_emulator.yaml"
        copy.write_text(yaml.safe_dump(config, sort_keys=False))
        return ["driver:=dynamixel", f"port:={self.port}", f"hardware_file:={copy}"]

    def send(self, command: str) -> str:
        self.process.stdin.write(command + "\n")
        self.process.stdin.flush()
        return self.process.stdout.readline().strip()

    def close(self) -> None:
        self.process.stdin.close()  # the emulator ends with its input
        try:
            self.process.wait(10)
        except subprocess.TimeoutExpired:
            stop(self.process)


class DriverServices:
    """The driver's ~estop and ~clear_fault, and the arm controller's action results as the driver sends them."""

    def __init__(self, controller: str = "arm_controller") -> None:
        rospy.wait_for_service("sixdof_control/estop", STARTUP_TIMEOUT)
        self.estop = rospy.ServiceProxy("sixdof_control/estop", SetBool)
        self.clear_fault = rospy.ServiceProxy("sixdof_control/clear_fault", Trigger)
        self.results: list[tuple[float, FollowJointTrajectoryActionResult]] = []
        self._sub = rospy.Subscriber(f"{controller}/follow_joint_trajectory/result", FollowJointTrajectoryActionResult,
                                     lambda msg: self.results.append((time.monotonic(), msg)))

    def aborted_after(self, since: float, timeout: float = 10.0) -> tuple[float, str]:
        """The first aborted result after `since` (time.monotonic()): (seconds after since, error_string)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for at, msg in list(self.results):
                if at >= since and msg.status.status == GoalStatus.ABORTED:
                    return at - since, msg.result.error_string
            time.sleep(0.01)
        raise AssertionError(f"no aborted goal within {timeout} s")

    def close(self) -> None:
        self._sub.unregister()


def arm_driver() -> ArmDriver:
    """An ArmDriver at full speed once move_group and the driver serve."""
    return ArmDriver(wait_for_servers=STARTUP_TIMEOUT, velocity_scaling=1.0, acceleration_scaling=1.0)


# Top-down with the tip's x axis along -x, as the paper's home pose (rpy (-180, 0.688, 179.995) deg): the wrist stays
# near its zero, away from joint4's +-pi limits.
DOWN = [math.pi, 0.0, math.pi]


def top_down(x: float, y: float, z: float) -> np.ndarray:
    """The tip link at (x, y, z), its z axis (the approach) pointing down, rpy DOWN."""
    pose = np.eye(4)
    pose[:3, :3] = np.diag([-1.0, 1.0, -1.0])  # rpy (pi, 0, pi)
    pose[:3, 3] = (x, y, z)
    return pose


def pick_sequence(arm: ArmDriver, pick: tuple[float, float], place: tuple[float, float], high: float,
                  low: float) -> None:
    """The stages of a pick and place without an object: open, above the pick point, straight down, close, lift,
    above the place point, down, open, retreat. Each must succeed."""
    assert arm.gripper_open(), arm.last_failure
    assert arm.moveto_xyzrpy([pick[0], pick[1], high, *DOWN]), arm.last_failure
    assert arm.move_straight(top_down(pick[0], pick[1], low), "approach", avoid_collisions=False), arm.last_failure
    closed = arm.gripper.close()
    assert closed.reached_goal, f"the gripper did not close (position {closed.position})"
    assert arm.move_straight(top_down(pick[0], pick[1], high), "lift", avoid_collisions=False), arm.last_failure
    assert arm.moveto_xyzrpy([place[0], place[1], high, *DOWN]), arm.last_failure
    assert arm.move_straight(top_down(place[0], place[1], low), "place", avoid_collisions=False), arm.last_failure
    assert arm.gripper_open(), arm.last_failure
    assert arm.move_straight(top_down(place[0], place[1], high), "retreat", avoid_collisions=False), arm.last_failure


def run_script(command: list[str], log: Path) -> None:
    """A script that must exit 0 within MOTION_TIMEOUT (its output in log)."""
    with open(log, "w") as out:
        done = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, timeout=MOTION_TIMEOUT)
    assert done.returncode == 0, f"{' '.join(command)} exited {done.returncode}: {log.read_text()[-2000:]}"
