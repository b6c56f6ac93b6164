"""A generated config package's real.launch (issue 23): the setup assistant's package of the seven_dof fixture (a
7R arm whose gripper's second finger mimics the first) runs real.launch (move_group, robot_state_publisher, no rviz,
wall clock) three ways, and a moveit_commander script plans and executes on each:
- driver:=mock: sixdof_control on the mock plugin with the package's config/hardware.yaml;
- driver:=dynamixel port:=<pty>: sixdof_control on the Protocol 2.0 servo emulator (ids from hardware.yaml);
- driver:=none: a process outside the launch serves the controllers (trajectory_driver.py: control_msgs only).
The fingers' controller maps the mimic finger to its master (hardware.yaml lists actuated joints only); joint_states
carry both fingers. Private ROS master; one launch at a time.

    python -m pytest test/ros/real_launch.py
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from pathlib import Path

import moveit_commander
import pytest
import rosnode
import rospy
import yaml
from e2e import STARTUP_TIMEOUT
from generated import arm_commander, generate_package, plan_and_execute_joint_goal, start, stop, workspace_fixture
from real_stack import Emulator, launch
from sensor_msgs.msg import JointState

ROBOT, DESCRIPTION = "seven_dof", "urdf/seven_dof.urdf.xacro"
DRIVER = Path(__file__).resolve().parent / "trajectory_driver.py"
TOLERANCE = 0.02  # rad: the controllers' goal tolerance and the servos' settling


@dataclass
class Package:
    name: str
    path: Path
    root: Path
    controllers: dict[str, list[str]]  # controller_list: name -> joints
    servos: list[int]  # hardware.yaml's dynamixel ids


workspace = workspace_fixture("real_launch", sim_time=False)


@pytest.fixture(scope="module")
def package(workspace: Path) -> Package:
    name, path = generate_package(ROBOT, DESCRIPTION, workspace)
    config = yaml.safe_load((path / "config" / "controllers.yaml").read_text())
    hardware = yaml.safe_load((path / "config" / "hardware.yaml").read_text())
    servos = [entry["id"] for entry in hardware["dynamixel"]["joints"].values()]
    moveit_commander.roscpp_initialize(sys.argv)
    return Package(name, path, workspace, {c["name"]: list(c["joints"]) for c in config["controller_list"]}, servos)


def joint_states(names: list[str]) -> list[float]:
    """The names' positions in the next joint_states message that has them all (external drivers publish a
    message per controller)."""
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while True:
        msg = rospy.wait_for_message("joint_states", JointState, timeout=STARTUP_TIMEOUT)
        positions = dict(zip(msg.name, msg.position, strict=True))
        if all(n in positions for n in names):
            return [positions[n] for n in names]
        assert time.monotonic() < deadline, f"no joint_states with {names}"


def plan_and_execute() -> None:
    """The arm to a joint goal (plan, then execute) and to a named state (go); the gripper open and closed, both
    fingers following."""
    robot, arm = arm_commander()
    names = arm.get_active_joints()
    goal = plan_and_execute_joint_goal(arm)
    time.sleep(0.5)  # the servos settle
    for joint, reached, wanted in zip(names, joint_states(names), goal, strict=True):
        assert abs(reached - wanted) < TOLERANCE, f"{joint} at {reached:.4f}, goal {wanted:.4f}"
    named = arm.get_named_targets()[0]
    assert arm.go(named, wait=True), f"go('{named}'): {arm.last_error}"
    hand = next(g for g in robot.get_group_names() if g != arm.get_name())
    gripper = moveit_commander.MoveGroupCommander(hand, wait_for_servers=STARTUP_TIMEOUT)
    fingers = robot.get_joint_names(hand)
    for state in ("open", "close"):
        assert gripper.go(state, wait=True), f"gripper go('{state}'): {gripper.last_error}"
        time.sleep(0.5)
        values = joint_states(fingers)
        assert max(values) - min(values) < TOLERANCE, f"the fingers {fingers} disagree: {values}"


def test_mock(package: Package) -> None:
    stack = launch([package.name, "real.launch", "driver:=mock", "rviz:=false"], package.root / "mock.log")
    try:
        plan_and_execute()
    finally:
        stop(stack)


def test_dynamixel_on_the_emulator(package: Package) -> None:
    emulator = Emulator(package.servos)
    driver = emulator.driver_args(package.path / "config" / "hardware.yaml", package.root)
    stack = launch([package.name, "real.launch", *driver, "rviz:=false"], package.root / "dynamixel.log")
    try:
        plan_and_execute()
    finally:
        stop(stack)
        emulator.close()


def test_an_external_driver(package: Package) -> None:
    drivers = [
        start([sys.executable, str(DRIVER), controller, *joints, f"__name:={controller}_driver"],
              package.root / f"driver_{controller}.log")
        for controller, joints in package.controllers.items()
    ]
    stack = launch([package.name, "real.launch", "rviz:=false"], package.root / "none.log")
    try:
        _, arm = arm_commander()
        begin = arm.get_current_joint_values()
        goal = [value + (0.3 if i % 2 == 0 else -0.3) for i, value in enumerate(begin)]
        assert arm.go(goal, wait=True), f"go: {arm.last_error}"
        names = arm.get_active_joints()
        for joint, reached, wanted in zip(names, joint_states(names), goal, strict=True):
            assert abs(reached - wanted) < 1e-3, f"{joint} at {reached:.4f}, goal {wanted:.4f}"
        assert "/sixdof_control" not in rosnode.get_node_names(), "real.launch driver:=none started a driver"
    finally:
        stop(stack)
        for d in drivers:
            stop(d)
