"""Any arm, end to end: for each fixture robot of sixdof_test_robots, the setup assistant generates its config package
into a temporary workspace, the package's demo.launch runs headless, a pose goal is planned and executed through
sixdof_commander and the reached pose is checked by forward kinematics; then rviz opens the package's config (on
the X display the test runs on: xvfb-run) and its Goal State marker solves a goal. One launched stack per robot.

    xvfb-run -a -s "-screen 0 1280x1024x24" python -m pytest test/ros/any_arm.py -k seven_dof
"""

from __future__ import annotations

import os
import re
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
import rospy
from e2e import STARTUP_TIMEOUT, settled_joint_state
from generated import generate_package, launch_demo, stop_demo, workspace_fixture
from geometry_msgs.msg import PoseStamped
from moveit_msgs.msg import RobotState
from moveit_msgs.srv import GetPositionFK, GetStateValidity
from rosgraph_msgs.msg import Log
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import JointState
from sixdof_commander import ArmDriver, Gripper, MoveGroup, SixdofCommanderError
from urdf_parser_py.urdf import URDF

from sixdof_rviz.rviz_process import RvizProcess
from sixdof_rviz.screenshots import marker_sphere_mask, settled_screenshot

# robot name -> (description file in sixdof_test_robots, has a gripper)
ROBOTS = {
    "ur_like": ("urdf/ur_like.urdf.xacro", False),
    "seven_dof": ("urdf/seven_dof.urdf.xacro", True),
    "mounted": ("urdf/mounted.urdf", False),
}
SEED = 10
# The reached pose against the goal: the planner's default goal tolerances, plus the servos' settling.
POSITION_TOLERANCE = 0.005  # m
ANGLE_TOLERANCE = 0.02  # rad
# rviz logs these when the optional package media_export is missing; they are harmless.
HARMLESS = ("no such package media_export", "error while executing command")


workspace = workspace_fixture("any_arm")


@dataclass
class Stack:
    robot: str
    workspace: Path
    package: Path
    has_gripper: bool
    group: str  # the arm's planning group (the SRDF's first chain group)
    tip: str
    root_link: str
    limits: dict[str, tuple[float, float]]  # of the group's joints


def chain_group(srdf: str) -> tuple[str, str]:
    """(name, tip link) of the SRDF's first chain group."""
    match = re.search(r'<group name="([^"]+)">\s*<chain base_link="[^"]+" tip_link="([^"]+)"', srdf)
    assert match, "the generated SRDF has no chain group"
    return match.group(1), match.group(2)


@pytest.fixture(scope="module", params=sorted(ROBOTS))
def stack(request: pytest.FixtureRequest, workspace: Path) -> Iterator[Stack]:
    """The robot's generated package and its demo.launch headless, up until move_group and the simulator answer."""
    robot = request.param
    description, has_gripper = ROBOTS[robot]
    name, package = generate_package(robot, description, workspace)
    launch = launch_demo(name, robot, workspace, ("compute_fk", "check_state_validity", "sixdof_sim/get_object_state"))
    try:
        group, tip = chain_group(rospy.get_param("robot_description_semantic"))
        urdf = URDF.from_xml_string(rospy.get_param("robot_description"))
        limits = {}
        for joint in urdf.joints:
            if joint.type in ("revolute", "prismatic"):
                limits[joint.name] = (joint.limit.lower, joint.limit.upper)
            elif joint.type == "continuous":
                limits[joint.name] = (-np.pi, np.pi)
        yield Stack(robot, workspace, package, has_gripper, group, tip, urdf.get_root(), limits)
    finally:
        stop_demo(launch, "any_arm")


def fk(link: str, names: list[str], positions: list[float]) -> PoseStamped:
    state = RobotState()
    state.is_diff = True
    state.joint_state.name = list(names)
    state.joint_state.position = list(positions)
    response = rospy.ServiceProxy("compute_fk", GetPositionFK)(fk_link_names=[link], robot_state=state)
    assert response.error_code.val == response.error_code.SUCCESS, f"compute_fk of '{link}': {response.error_code.val}"
    return response.pose_stamped[0]


def pose_arrays(pose: PoseStamped) -> tuple[np.ndarray, Rotation]:
    p, q = pose.pose.position, pose.pose.orientation
    return np.array([p.x, p.y, p.z]), Rotation.from_quat([q.x, q.y, q.z, q.w])


def reachable_goal(stack: Stack, joints: list[str]) -> PoseStamped:
    """The tip pose of a seeded random collision-free configuration within +-1.2 rad (or m) of zero."""
    rng = np.random.default_rng(SEED)
    validity = rospy.ServiceProxy("check_state_validity", GetStateValidity)
    for _ in range(200):
        values = [rng.uniform(max(stack.limits[j][0], -1.2), min(stack.limits[j][1], 1.2)) for j in joints]
        state = RobotState(is_diff=True)
        state.joint_state.name = joints
        state.joint_state.position = values
        if validity(robot_state=state, group_name=stack.group).valid:
            return fk(stack.tip, joints, values)
    raise AssertionError(f"no collision-free configuration of group '{stack.group}' in 200 samples")


def test_pose_goal_is_reached(stack: Stack) -> None:
    group = MoveGroup(stack.group, wait_for_servers=STARTUP_TIMEOUT)
    joints = group.get_active_joints()
    goal = reachable_goal(stack, joints)
    group.set_pose_target(goal, stack.tip)
    assert group.go(wait=True), f"{stack.robot}: {group.last_error.message}"
    reached = settled_joint_state()
    position, rotation = pose_arrays(fk(stack.tip, reached.name, reached.position))
    goal_position, goal_rotation = pose_arrays(goal)
    error = float(np.linalg.norm(position - goal_position))
    angle = (rotation.inv() * goal_rotation).magnitude()
    rospy.loginfo("%s: pose goal reached within %.2f mm, %.3f deg", stack.robot, error * 1e3, np.degrees(angle))
    assert error < POSITION_TOLERANCE, f"{stack.robot}: reached {position}, goal {goal_position}"
    assert angle < ANGLE_TOLERANCE, f"{stack.robot}: orientation off by {np.degrees(angle):.2f} deg"


def test_gripper_works_or_names_what_is_missing(stack: Stack) -> None:
    if not stack.has_gripper:
        with pytest.raises(SixdofCommanderError, match="has no gripper: its SRDF has no group 'gripper'"):
            Gripper(wait_for_servers=10.0)
        # ArmDriver works without a gripper: the arm moves, the gripper methods name what is missing.
        driver = ArmDriver(group_name=stack.group, wait_for_servers=10.0)
        assert driver.gripper is None
        for method, args in ((driver.gripper_open, ()), (driver.gripper_close, ()), (driver.pick, ("box",))):
            with pytest.raises(SixdofCommanderError, match=r"has no gripper: move_group has no grasping information"):
                method(*args)
        assert driver.moveto_named("home"), f"{stack.robot}: {driver.last_failure}"
        return
    gripper = Gripper(wait_for_servers=STARTUP_TIMEOUT)
    for command, target in ((gripper.close, gripper.close_position), (gripper.open, gripper.open_position)):
        result = command()
        assert result.reached_goal, f"{stack.robot}: gripper stopped at {result.position}, goal {target}"
    # ArmDriver's grasp geometry, the package's grasping.yaml from move_group's get_robot_model: the fixture's
    # fingertips end exactly at the tcp (both 0.1 m below the hand), so they reach 0 beyond it.
    driver = ArmDriver(group_name=stack.group, wait_for_servers=STARTUP_TIMEOUT)
    assert driver.grasp_spec.reach == pytest.approx(0.0, abs=1e-9), f"{stack.robot}: {driver.grasp_spec}"


class Rviz:
    """rviz with a config on this process's X display (started again when Mesa kills it in its first seconds:
    sixdof_rviz.rviz_process); collects what its nodes log as errors."""

    def __init__(self, config: Path, log: Path) -> None:
        self.errors: list[str] = []
        self.lock = threading.Lock()
        self.sub = rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        self.process = RvizProcess(["rviz", "-d", str(config)], log)

    def on_log(self, msg: Log) -> None:
        if msg.level >= Log.ERROR and "rviz" in msg.name and not any(h in msg.msg for h in HARMLESS):
            with self.lock:
                self.errors.append(msg.msg)

    def window(self) -> str:
        """The id of rviz's main window, once rviz has stayed up with it mapped."""
        try:
            return self.process.wait_up(STARTUP_TIMEOUT)
        except RuntimeError as e:
            raise AssertionError(str(e)) from e

    def yellow_pixels(self, window: str) -> int:
        """Pixels of the Goal State marker's yellow drag sphere in the 3D view of the window, once rviz's drawing is
        still (the robot and any marker drawn)."""
        image = settled_screenshot(window, timeout=STARTUP_TIMEOUT)
        return int(marker_sphere_mask(image[:, 400:]).sum())  # right of the Displays panel

    def close(self) -> list[str]:
        self.process.stop()
        self.sub.unregister()
        with self.lock:
            return list(self.errors)


def goal_state_config(config: Path, out: Path) -> Path:
    """The package's rviz config with the Goal State display enabled and its group left to the model."""
    text = config.read_text()
    text, enabled = re.subn(r"(- Class: sixdof_rviz/GoalState\n\s+Enabled:) false", r"\1 true", text)
    assert enabled == 1, f"{config} has no disabled Goal State display"
    text = re.sub(r"(\n\s+Planning Group:) \S+", r"\1 ''", text)
    out.write_text(text)
    return out


def test_rviz_config_opens_and_its_goal_marker_solves(stack: Stack) -> None:
    workspace = stack.workspace
    assert os.environ.get("DISPLAY"), "rviz needs an X display: run under xvfb-run"
    config = stack.package / "config" / "motion_planning.rviz"
    # The package's config as generated: Goal State disabled, so no drag sphere anywhere.
    rviz = Rviz(config, workspace / f"{stack.robot}_rviz.log")
    try:
        window = rviz.window()
        disabled_yellow = rviz.yellow_pixels(window)
    finally:
        errors = rviz.close()
    assert errors == [], f"{stack.robot}: rviz logged errors: {errors}"
    assert disabled_yellow == 0, f"{stack.robot}: {disabled_yellow} drag-sphere pixels with Goal State disabled"

    # Goal State enabled: a pose published on its goal pose topic is solved and published as the goal state.
    joints = MoveGroup(stack.group, wait_for_servers=STARTUP_TIMEOUT).get_active_joints()
    goal = reachable_goal(stack, joints)
    goal.header.frame_id = stack.root_link
    rviz = Rviz(
        goal_state_config(config, workspace / f"{stack.robot}_goal.rviz"), workspace / f"{stack.robot}_rviz2.log"
    )
    solved: list[JointState] = []
    goal_position, _ = pose_arrays(goal)

    def on_goal_state(msg: JointState) -> None:
        if set(joints) <= set(msg.name):
            position, _ = pose_arrays(fk(stack.tip, msg.name, msg.position))
            if np.linalg.norm(position - goal_position) < 0.001:
                solved.append(msg)

    sub = rospy.Subscriber("sixdof_rviz/goal_state", JointState, on_goal_state, queue_size=10)
    publisher = rospy.Publisher("sixdof_rviz/goal_pose", PoseStamped, queue_size=1, latch=True)
    try:
        rviz.window()
        deadline = time.monotonic() + STARTUP_TIMEOUT
        while not solved and time.monotonic() < deadline:
            publisher.publish(goal)  # again until rviz has subscribed and answered
            time.sleep(1.0)
    finally:
        sub.unregister()
        publisher.unregister()
        errors = rviz.close()
    assert solved, f"{stack.robot}: the Goal State display never published a goal state at the goal pose"
    assert errors == [], f"{stack.robot}: rviz logged errors: {errors}"
