"""The sixdof arm as a real robot (issue 23): sixdof_bringup's real.launch (robot_state_publisher, move_group, no
rviz, wall clock) with the sixdof_control driver on the mock plugin, then on the dynamixel plugin driving the Protocol
2.0 servo emulator. On each: the paper's script (paper_figure6.py: ArmDriver.moveto_xyzrpy to the home and target
poses), a pick motion sequence without objects, and the e-stop (motion stops, goals are refused until it is
released); on the emulator also a servo that stops answering in the middle of a motion (the driver aborts within 1 s
naming the joint; after the servo is back and the fault cleared, motions work again). The mock's own faults are
sixdof_control's driver.test. Private ROS master.

    python -m pytest test/ros/real_robot.py
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import rospkg
from generated import stop, workspace_fixture
from real_stack import FAULT_BOUND, DriverServices, Emulator, arm_driver, launch, pick_sequence, run_script
from sixdof_commander import ArmDriver

SERVOS = list(range(1, 8))  # sixdof_description's hardware.yaml: joint1..6 and finger1_joint


workspace = workspace_fixture("real_robot", sim_time=False)


def slow_motion(arm: ArmDriver) -> tuple[list[float], threading.Thread, list[bool]]:
    """The first joint turning 1.2 rad at 20 % speed (over 3 s), on a thread: (the start, the thread, the list its
    go()'s outcome lands in)."""
    start = arm.arm.get_current_joint_values()
    target = list(start)
    target[0] += -1.2 if start[0] > 0.0 else 1.2
    arm.arm.set_max_velocity_scaling_factor(0.2)
    outcome: list[bool] = []
    thread = threading.Thread(target=lambda: outcome.append(arm.arm.go(target, wait=True)))
    thread.start()
    return start, thread, outcome


def check_estop(arm: ArmDriver, services: DriverServices) -> None:
    """An e-stop in the middle of a motion aborts it within FAULT_BOUND, motions are refused until it is released."""
    start, thread, outcome = slow_motion(arm)
    time.sleep(1.5)
    pressed = time.monotonic()
    assert services.estop(True).success
    after, why = services.aborted_after(pressed)
    assert after <= FAULT_BOUND, f"the e-stop aborted the goal after {after:.2f} s"
    assert "e-stop" in why, why
    thread.join(60.0)
    assert outcome == [False], "the motion under e-stop did not fail"
    assert not arm.arm.go(start, wait=True), "a motion was accepted during the e-stop"
    assert "e-stop" in arm.arm.last_error.message, arm.arm.last_error.message
    assert services.estop(False).success
    arm.arm.set_max_velocity_scaling_factor(1.0)
    assert arm.arm.go(start, wait=True), arm.arm.last_error.message


@contextlib.contextmanager
def real_launch(args: list[str], log: Path) -> Iterator[tuple[ArmDriver, DriverServices]]:
    """sixdof_bringup's real.launch with args (no rviz); an ArmDriver and the driver's services once they serve."""
    stack = launch(["sixdof_bringup", "real.launch", "rviz:=false", *args], log)
    services = None
    try:
        arm = arm_driver()
        services = DriverServices()
        yield arm, services
    finally:
        if services:
            services.close()
        stop(stack)


def test_sixdof_arm_on_the_mock(workspace: Path) -> None:
    with real_launch(["driver:=mock"], workspace / "mock.log") as (arm, services):
        run_script(["rosrun", "sixdof_scripts", "paper_figure6.py"], workspace / "paper_mock.log")
        pick_sequence(arm, (0.40, -0.15), (0.40, 0.20), high=0.25, low=0.17)
        check_estop(arm, services)


def test_sixdof_arm_on_dynamixel_servos(workspace: Path) -> None:
    emulator = Emulator(SERVOS)
    try:
        hardware = Path(rospkg.RosPack().get_path("sixdof_description")) / "config" / "hardware.yaml"
        with real_launch(emulator.driver_args(hardware, workspace), workspace / "dynamixel.log") as (
            arm,
            services,
        ):
            run_script(["rosrun", "sixdof_scripts", "paper_figure6.py"], workspace / "paper_dynamixel.log")
            pick_sequence(arm, (0.40, -0.15), (0.40, 0.20), high=0.25, low=0.17)
            check_estop(arm, services)
            # joint3's servo (id 3) stops answering in the middle of a motion.
            start, thread, outcome = slow_motion(arm)
            time.sleep(1.5)
            removed = time.monotonic()
            assert emulator.send("remove 3") == "ok"
            after, why = services.aborted_after(removed)
            assert after <= FAULT_BOUND, f"the lost servo aborted the goal after {after:.2f} s: {why}"
            assert "joint3" in why, why
            thread.join(60.0)
            assert outcome == [False], "the motion with a lost servo did not fail"
            assert "joint3" in arm.arm.last_error.message, arm.arm.last_error.message
            assert emulator.send("restore 3") == "ok"
            assert services.clear_fault().success
            arm.arm.set_max_velocity_scaling_factor(1.0)
            assert arm.arm.go(start, wait=True), arm.arm.last_error.message
    finally:
        emulator.close()
