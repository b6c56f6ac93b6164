"""move_group drives a robot's own driver (issue 22): a fixture robot's config package, written by the setup
assistant, runs its move_group.launch (move_group alone, as with real hardware) beside a separate driver process
that speaks only control_msgs and sensor_msgs (trajectory_driver.py: a minimal FollowJointTrajectory server
publishing joint_states, no simulator). A moveit_commander script plans and executes to a joint goal and goes to a
named state; the driver's joint_states end at the goals. Private ROS master, wall clock (there is no /clock).

    python -m pytest test/ros/external_driver.py
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import moveit_commander
import pytest
import rosgraph
import rospy
import yaml
from e2e import STARTUP_TIMEOUT
from generated import generate_package, start, start_master, stop, wait_for_move_group
from moveit_msgs.msg import MoveItErrorCodes
from sensor_msgs.msg import JointState

ROBOT, DESCRIPTION = "ur_like", "urdf/ur_like.urdf.xacro"
DRIVER = Path(__file__).resolve().parent / "trajectory_driver.py"
TOLERANCE = 1e-3  # rad: the driver follows the trajectory exactly; this covers the goal tolerance


@dataclass
class Robot:
    controllers: dict[str, list[str]]  # the package's controller_list: name -> joints


@pytest.fixture(scope="module")
def robot(request: pytest.FixtureRequest) -> Iterator[Robot]:
    """The generated package's move_group.launch and one driver process per controller (node `<controller>_driver`),
    on a master of their own."""
    root = Path(tempfile.mkdtemp(prefix="external_driver_"))
    core = start_master(root)
    processes = []
    try:
        name, package = generate_package(ROBOT, DESCRIPTION, root)
        config = yaml.safe_load((package / "config" / "controllers.yaml").read_text())
        controllers = {c["name"]: list(c["joints"]) for c in config["controller_list"]}
        for controller, joints in controllers.items():
            command = [sys.executable, str(DRIVER), controller, *joints, f"__name:={controller}_driver"]
            processes.append(start(command, root / f"driver_{controller}.log"))
        processes.append(start(["roslaunch", name, "move_group.launch"], root / "move_group.log"))
        moveit_commander.roscpp_initialize(sys.argv)
        rospy.init_node("external_driver_test", disable_signals=True)
        yield Robot(controllers)
    finally:
        for process in reversed(processes):
            stop(process)
        stop(core)
    if request.session.testsfailed:
        print(f"external_driver: logs of the failed run kept in {root}")
    else:
        shutil.rmtree(root, ignore_errors=True)


def joint_positions(names: list[str]) -> dict[str, float]:
    """The driver's latest joint_states, for names."""
    msg = rospy.wait_for_message("joint_states", JointState, timeout=STARTUP_TIMEOUT)
    positions = dict(zip(msg.name, msg.position, strict=True))
    return {n: positions[n] for n in names}


def assert_at(names: list[str], goal: list[float]) -> None:
    reached = joint_positions(names)
    for joint, value in zip(names, goal, strict=True):
        assert abs(reached[joint] - value) < TOLERANCE, f"{joint} at {reached[joint]:.5f}, goal {value:.5f}"


def test_move_group_drives_a_control_msgs_driver(robot: Robot) -> None:
    model = wait_for_move_group()
    group = max(model.get_group_names(), key=lambda g: len(model.get_active_joint_names(g)))
    commander = moveit_commander.MoveGroupCommander(group, wait_for_servers=STARTUP_TIMEOUT)
    # move_group's controller actions are control_msgs', and only the drivers publish joint_states.
    master = rosgraph.Master("/external_driver_test")
    types = dict(master.getTopicTypes())
    for controller in robot.controllers:
        assert types[f"/{controller}/follow_joint_trajectory/goal"] == "control_msgs/FollowJointTrajectoryActionGoal"
    publishers = dict(master.getSystemState()[0])
    assert sorted(publishers["/joint_states"]) == sorted(f"/{c}_driver" for c in robot.controllers)

    commander.set_max_velocity_scaling_factor(1.0)
    commander.set_max_acceleration_scaling_factor(1.0)
    names = commander.get_active_joints()
    start = commander.get_current_joint_values()
    goal = [value + (0.3 if i % 2 == 0 else -0.3) for i, value in enumerate(start)]
    success, plan, _, error_code = commander.plan(goal)
    assert success, f"plan: {commander.last_error}"
    assert error_code.val == MoveItErrorCodes.SUCCESS
    assert commander.execute(plan, wait=True), f"execute: {commander.last_error}"
    assert_at(names, goal)

    named = commander.get_named_targets()[0]
    assert commander.go(named, wait=True), f"go('{named}'): {commander.last_error}"
    values = commander.get_named_target_values(named)
    assert_at(names, [values[n] for n in names])
