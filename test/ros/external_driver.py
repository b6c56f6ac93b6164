"""move_group drives a robot's own driver (issue 22): a fixture robot's config package, written by the setup
assistant, runs its move_group.launch (move_group alone, as with real hardware) beside a separate driver process
that speaks only control_msgs and sensor_msgs (trajectory_driver.py: a minimal FollowJointTrajectory server
publishing joint_states, no simulator). A moveit_commander script plans and executes to a joint goal and goes to a
named state; the driver's joint_states end at the goals. Private ROS master, wall clock (there is no /clock).

    python -m pytest test/ros/external_driver.py
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import moveit_commander
import pytest
import rosgraph
import rospy
import yaml
from e2e import STARTUP_TIMEOUT
from generated import arm_commander, generate_package, plan_and_execute_joint_goal, start, stop, workspace_fixture
from sensor_msgs.msg import JointState

ROBOT, DESCRIPTION = "ur_like", "urdf/ur_like.urdf.xacro"
DRIVER = Path(__file__).resolve().parent / "trajectory_driver.py"
TOLERANCE = 1e-3  # rad: the driver follows the trajectory exactly; this covers the goal tolerance


@dataclass
class Robot:
    controllers: dict[str, list[str]]  # the package's controller_list: name -> joints


workspace = workspace_fixture("external_driver", sim_time=False)


@pytest.fixture(scope="module")
def robot(workspace: Path) -> Iterator[Robot]:
    """The generated package's move_group.launch and one driver process per controller (node `<controller>_driver`),
    on the workspace's master."""
    processes = []
    try:
        name, package = generate_package(ROBOT, DESCRIPTION, workspace)
        config = yaml.safe_load((package / "config" / "controllers.yaml").read_text())
        controllers = {c["name"]: list(c["joints"]) for c in config["controller_list"]}
        for controller, joints in controllers.items():
            command = [sys.executable, str(DRIVER), controller, *joints, f"__name:={controller}_driver"]
            processes.append(start(command, workspace / f"driver_{controller}.log"))
        processes.append(start(["roslaunch", name, "move_group.launch"], workspace / "move_group.log"))
        moveit_commander.roscpp_initialize(sys.argv)
        yield Robot(controllers)
    finally:
        for process in reversed(processes):
            stop(process)


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
    _, commander = arm_commander()
    # move_group's controller actions are control_msgs', and only the drivers publish joint_states.
    master = rosgraph.Master("/external_driver_test")
    types = dict(master.getTopicTypes())
    for controller in robot.controllers:
        assert types[f"/{controller}/follow_joint_trajectory/goal"] == "control_msgs/FollowJointTrajectoryActionGoal"
    publishers = dict(master.getSystemState()[0])
    assert sorted(publishers["/joint_states"]) == sorted(f"/{c}_driver" for c in robot.controllers)

    names = commander.get_active_joints()
    assert_at(names, plan_and_execute_joint_goal(commander))

    named = commander.get_named_targets()[0]
    assert commander.go(named, wait=True), f"go('{named}'): {commander.last_error}"
    values = commander.get_named_target_values(named)
    assert_at(names, [values[n] for n in names])
