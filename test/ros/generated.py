"""What the tests of generated config packages share (any_arm.py, any_gripper.py, external_driver.py,
real_launch.py; real_robot.py uses the workspace): a ROS master of the test's own, processes started in groups of
their own, a temporary workspace on ROS_PACKAGE_PATH, a fixture robot's package written by the setup assistant, its
demo.launch run headless until its services answer, stopping launched process groups, and moveit_commander's
plan and execute of a joint goal."""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

import moveit_commander
import pytest
import rosgraph
import rospkg
import rospy
from e2e import STARTUP_TIMEOUT
from moveit_msgs.msg import MoveItErrorCodes
from sensor_msgs.msg import JointState

from sixdof_test_support.processes import free_port, stop

FIXTURES = Path(rospkg.RosPack().get_path("sixdof_test_robots"))


def start(command: list[str], log: Path) -> subprocess.Popen:
    """command in a process group of its own, its output into log."""
    with open(log, "w") as out:
        return subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)


def start_master(root: Path) -> subprocess.Popen:
    """A roscore on a free port for this process and its children (ROS_MASTER_URI), with root (where the generated
    packages go) first on ROS_PACKAGE_PATH and the logs under root; returns once the master answers."""
    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://localhost:{port}"
    os.environ["ROS_PACKAGE_PATH"] = os.pathsep.join([str(root), os.environ.get("ROS_PACKAGE_PATH", "")])
    os.environ["ROS_LOG_DIR"] = str(root / "log")
    with open(root / "roscore.log", "w") as log:
        core = subprocess.Popen(
            ["roscore", "-p", str(port)], stdout=log, stderr=subprocess.STDOUT, start_new_session=True
        )
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while not rosgraph.is_master_online():
        assert core.poll() is None, f"roscore exited (see {root / 'roscore.log'})"
        assert time.monotonic() < deadline, "the ROS master did not come up"
        time.sleep(0.2)
    return core


def wait_for_move_group() -> moveit_commander.RobotCommander:
    """A RobotCommander once move_group serves the robot model (it may still be starting)."""
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while True:
        try:
            return moveit_commander.RobotCommander()
        except moveit_commander.MoveItCommanderException:
            assert time.monotonic() < deadline, "move_group did not come up"
            time.sleep(1.0)


def generate_package(robot: str, description: str | Path, workspace: Path, xacro_args: str = "") -> tuple[str, Path]:
    """The setup assistant's config package of the fixture robot `robot` (description: its file in sixdof_test_robots,
    or an absolute path, expanded with xacro_args) written into workspace without answers: (package name
    `<robot>_sixdof_config`, its folder)."""
    name = f"{robot}_sixdof_config"
    command = ["rosrun", "sixdof_setup_assistant", "setup_assistant", "--urdf", str(FIXTURES / description),
               "--package-out", str(workspace), "--name", name]
    if xacro_args:
        command += ["--xacro-args", xacro_args]
    generated = subprocess.run(command, capture_output=True, text=True, timeout=STARTUP_TIMEOUT)
    assert generated.returncode == 0, f"setup_assistant failed on {description}: {generated.stderr}"
    package = workspace / name
    assert (package / "launch" / "demo.launch").is_file(), generated.stdout
    return name, package


def session_workspace(request: pytest.FixtureRequest, test: str, sim_time: bool = True) -> Iterator[Path]:
    """For a session fixture: a temporary workspace on ROS_PACKAGE_PATH and a ROS master of the test's own, which
    every robot's stack uses in turn; this process's node `<test>_test` follows the simulated clock (sim_time) or
    the wall clock. The workspace (with the logs) is kept when a test failed."""
    root = Path(tempfile.mkdtemp(prefix=f"{test}_"))
    core = start_master(root)
    if sim_time:
        rosgraph.Master(f"/{test}").setParam("/use_sim_time", True)
    rospy.init_node(f"{test}_test", disable_signals=True)
    yield root
    stop(core)
    if request.session.testsfailed:
        print(f"{test}: logs of the failed run kept in {root}")
    else:
        shutil.rmtree(root, ignore_errors=True)


def workspace_fixture(test: str, sim_time: bool = True) -> Callable[..., Iterator[Path]]:
    """The session fixture `workspace` of a test module (`workspace = workspace_fixture("any_arm")`):
    session_workspace's workspace and master."""

    @pytest.fixture(scope="session")
    def workspace(request: pytest.FixtureRequest) -> Iterator[Path]:
        yield from session_workspace(request, test, sim_time)

    return workspace


def arm_commander() -> tuple[moveit_commander.RobotCommander, moveit_commander.MoveGroupCommander]:
    """move_group's robot once it serves it, and a commander of its group with the most active joints, at full
    velocity and acceleration."""
    robot = wait_for_move_group()
    group = max(robot.get_group_names(), key=lambda g: len(robot.get_active_joint_names(g)))
    arm = moveit_commander.MoveGroupCommander(group, wait_for_servers=STARTUP_TIMEOUT)
    arm.set_max_velocity_scaling_factor(1.0)
    arm.set_max_acceleration_scaling_factor(1.0)
    return robot, arm


def plan_and_execute_joint_goal(arm: moveit_commander.MoveGroupCommander) -> list[float]:
    """Plans to the current joint values moved by 0.3 rad (alternating signs), checks the plan's outcome, executes
    it; returns the goal."""
    start = arm.get_current_joint_values()
    goal = [value + (0.3 if i % 2 == 0 else -0.3) for i, value in enumerate(start)]
    success, plan, _, error_code = arm.plan(goal)
    assert success, f"plan: {arm.last_error}"
    assert error_code.val == MoveItErrorCodes.SUCCESS
    assert arm.execute(plan, wait=True), f"execute: {arm.last_error}"
    return goal


def launch_demo(name: str, robot: str, workspace: Path, services: Sequence[str]) -> subprocess.Popen:
    """The package `name`'s demo.launch headless (its output in workspace/<robot>_demo.log), once `services` answer
    and joint_states come; the launch is stopped if they do not within STARTUP_TIMEOUT."""
    log_path = workspace / f"{robot}_demo.log"
    with open(log_path, "w") as log:
        launch = subprocess.Popen(
            ["roslaunch", name, "demo.launch", "headless:=true"],
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    try:
        deadline = time.monotonic() + STARTUP_TIMEOUT
        for service in services:
            while True:
                assert launch.poll() is None, f"{name} demo.launch ended (see {log_path})"
                assert time.monotonic() < deadline, f"no service '{service}' from {name} demo.launch"
                try:
                    rospy.wait_for_service(service, timeout=1.0)
                    break
                except rospy.ROSException:
                    pass
        rospy.wait_for_message("joint_states", JointState, timeout=STARTUP_TIMEOUT)
    except BaseException:
        stop(launch)
        raise
    return launch


def stop_demo(launch: subprocess.Popen, test: str) -> None:
    """Stops a launch_demo stack; the next robot's stack starts from an empty parameter server (roscore's own
    parameters aside)."""
    stop(launch)
    master = rosgraph.Master(f"/{test}")
    kept = {"run_id", "rosversion", "rosdistro", "use_sim_time"}
    for top in {key.split("/")[1] for key in master.getParamNames()} - kept:
        master.deleteParam("/" + top)
