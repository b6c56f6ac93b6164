"""Any gripper, end to end: for each fixture robot with a gripper (sixdof_test_robots), the setup assistant writes its
config package without answers into a temporary workspace, the package's demo.launch runs headless, and ArmDriver
(the commander's pick and place, which takes the TCP, the gripper's states and widths, the arm group and the home
state from the package through move_group) picks and places a cube, an upright cylinder and a sphere of 3 and 6 cm,
each spawned on the table, through the simulator's grasp fix (configured from the package's grasping.yaml), and
refuses a place whose descent would drive the object into the table. One launched stack per robot:
- seven_dof_hand: a 7-DoF arm with a prismatic two-finger hand and no `tcp` link;
- six_r_jaw: the 6R arm of six_r_adaptive.urdf.xacro with revolute jaws that open at their upper limit;
- six_r_adaptive: the same arm with its default 2F-style gripper: a revolute master and five mimic joints (one with a
  negative multiplier and limits that disagree with it), no inertias on its moving links;
- sixdof: the sixdof arm of sixdof_description, unchanged (its own `tcp` link, prismatic fingers), generated without
  the answers its CAD generator writes.

    python -m pytest test/ros/any_gripper.py -k six_r_jaw
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import pytest
import rospkg
import rospy
from e2e import STARTUP_TIMEOUT, planning_scene
from generated import FIXTURES, generate_package, launch_demo, stop_demo, workspace_fixture
from geometry_msgs.msg import Pose
from moveit_msgs.msg import PlanningSceneComponents
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import ArmDriver
from sixdof_commander.straight_moves import UNREACHABLE
from std_msgs.msg import ColorRGBA

from sixdof_bringup.placement import placement
from sixdof_msgs.msg import SimObject
from sixdof_msgs.srv import DeleteObject, GetObjectState, SpawnObject

# robot -> (description, xacro arguments)
ROBOTS = {
    "seven_dof_hand": (FIXTURES / "urdf/seven_dof_hand.urdf.xacro", ""),
    "six_r_jaw": (FIXTURES / "urdf/six_r_adaptive.urdf.xacro", "gripper:=jaw"),
    "six_r_adaptive": (FIXTURES / "urdf/six_r_adaptive.urdf.xacro", ""),
    "sixdof": (Path(rospkg.RosPack().get_path("sixdof_description")) / "urdf/sixdof.urdf", ""),
}
OBJECT = "test_object"
# (shape, width, height, start x y yaw, place x y): 3 and 6 cm of each shape, at different spots and yaws of the
# table in front of the robot.
CASES = [
    ("cube", 0.03, 0.03, (0.40, -0.15, 0.3), (0.40, 0.20)),
    ("cube", 0.06, 0.06, (0.45, 0.10, -0.7), (0.32, -0.10)),
    ("cylinder", 0.03, 0.06, (0.35, 0.20, 0.0), (0.45, -0.20)),
    ("cylinder", 0.06, 0.04, (0.30, -0.20, 0.0), (0.48, 0.05)),
    ("sphere", 0.03, 0.03, (0.48, -0.05, 0.0), (0.30, 0.15)),
    ("sphere", 0.06, 0.06, (0.33, 0.05, 0.0), (0.42, -0.22)),
]
TOLERANCE = 0.01  # m: where the released object rests, as bench/pick_bench.py's success
TILT = math.radians(10.0)


workspace = workspace_fixture("any_gripper")


@dataclass
class Stack:
    robot: str
    driver: ArmDriver


@pytest.fixture(scope="module", params=sorted(ROBOTS))
def stack(request: pytest.FixtureRequest, workspace: Path) -> Iterator[Stack]:
    """The robot's generated package and its demo.launch headless, up until move_group, the simulator and the scene
    mirror answer; the ArmDriver of the package's robot, at its home state."""
    robot = request.param
    description, xacro_args = ROBOTS[robot]
    name, _ = generate_package(robot, description, workspace, xacro_args)
    launch = launch_demo(name, robot, workspace, ("get_planning_scene", "sixdof_sim/spawn_object"))
    try:
        driver = ArmDriver(wait_for_servers=STARTUP_TIMEOUT)
        assert driver.moveto_named(driver.home), f"{robot}: {driver.last_failure}"
        yield Stack(robot, driver)
    finally:
        stop_demo(launch, "any_gripper")


def sim_object(shape: str, width: float, height: float, start: tuple[float, float, float]) -> SimObject:
    obj = SimObject(name=OBJECT, mass=0.1, friction=0.8, color=ColorRGBA(0.9, 0.5, 0.1, 1.0))
    if shape == "cube":
        obj.shape = SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[width] * 3)
    elif shape == "cylinder":
        obj.shape = SolidPrimitive(type=SolidPrimitive.CYLINDER, dimensions=[height, width / 2.0])
    else:
        obj.shape = SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[width / 2.0])
    x, y, yaw = start
    obj.pose = Pose()
    obj.pose.position.x, obj.pose.position.y, obj.pose.position.z = x, y, height / 2.0
    obj.pose.orientation.z, obj.pose.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return obj


def in_scene(present: bool) -> None:
    """Until the scene mirror has added (removed) the object; wall clock, the simulator runs free."""
    names = PlanningSceneComponents.WORLD_OBJECT_NAMES | PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
    deadline = time.monotonic() + 30.0
    while time.monotonic() < deadline:
        scene = planning_scene(names)
        known = {o.id for o in scene.world.collision_objects}
        known |= {a.object.id for a in scene.robot_state.attached_collision_objects}
        if (OBJECT in known) == present:
            return
        time.sleep(0.05)
    raise AssertionError(f"'{OBJECT}' {'never appeared in' if present else 'never left'} the planning scene")


@contextmanager
def spawned(driver: ArmDriver, what: str, obj: SimObject) -> Iterator[rospy.ServiceProxy]:
    """The object spawned on the table and in the planning scene (the simulator's get_object_state to look at it);
    afterwards it is deleted, the gripper opened and the arm at home."""
    spawn = rospy.ServiceProxy("sixdof_sim/spawn_object", SpawnObject)
    delete = rospy.ServiceProxy("sixdof_sim/delete_object", DeleteObject)
    response = spawn(obj)
    assert response.success, response.status_message
    try:
        rospy.sleep(0.3)  # settle (simulated time)
        in_scene(True)
        yield rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
    finally:
        delete(OBJECT)
        in_scene(False)
        driver.forget_held()
        assert driver.gripper_open(), f"{what}: {driver.last_failure}"
        assert driver.moveto_named(driver.home), f"{what}: {driver.last_failure}"


@pytest.mark.parametrize(("shape", "width", "height", "start", "place"), CASES)
def test_picks_and_places(
    stack: Stack,
    shape: str,
    width: float,
    height: float,
    start: tuple[float, float, float],
    place: tuple[float, float],
) -> None:
    driver = stack.driver
    what = f"{stack.robot}: {shape} {width * 100:.0f} cm from ({start[0]}, {start[1]}) to {place}"
    with spawned(driver, what, sim_object(shape, width, height, start)) as state:
        assert driver.grasp(OBJECT), f"{what}: {driver.last_failure}"
        assert driver.lift(), f"{what}: {driver.last_failure}"
        # The grasp fix of the package's grasping.yaml holds it, on the gripper's palm link.
        held = state(OBJECT)
        assert held.attached_to == driver.gripper_model.parent_link, f"{what}: held by '{held.attached_to}'"
        assert driver.release_at([place[0], place[1], height / 2.0]), f"{what}: {driver.last_failure}"
        assert driver.retreat(), f"{what}: {driver.last_failure}"
        rospy.sleep(0.5)
        final = state(OBJECT)
        assert final.attached_to == "", f"{what}: still held by '{final.attached_to}'"
        result = placement(final.object.pose, (place[0], place[1], height / 2.0))
        print(f"{what}: placed {result.error * 1000:.1f} mm off, tilted {math.degrees(result.tilt):.1f} deg")
        assert result.error < TOLERANCE, f"{what}: rests {result.error * 1000:.1f} mm off the target"
        assert result.tilt < TILT, f"{what}: tilted {math.degrees(result.tilt):.1f} deg"


def test_a_place_descent_into_the_table_is_refused(stack: Stack) -> None:
    """A place whose straight descent would drive the held object (and the fingers) into the table is refused as
    unreachable before the arm moves down, naming the collision; the object stays held, the place goes on."""
    driver = stack.driver
    width, start, place = 0.04, (0.40, -0.15, 0.3), (0.40, 0.15)
    with spawned(driver, stack.robot, sim_object("cube", width, width, start)) as state:
        assert driver.grasp(OBJECT) and driver.lift(), f"{stack.robot}: {driver.last_failure}"
        assert not driver.release_at([place[0], place[1], width / 2.0 - 0.03])
        assert driver.last_failure_kind == UNREACHABLE, driver.last_failure
        assert "would collide" in driver.last_failure, driver.last_failure
        # Stopped above the place: the object's bottom still clear of the table, the object held.
        tip = driver.arm.get_current_pose().pose.position.z
        assert tip > driver.place_tip([place[0], place[1]])[2, 3] + driver.approach_distance / 2.0, tip
        assert state(OBJECT).attached_to == driver.gripper_model.parent_link
        assert driver.release_at([place[0], place[1], width / 2.0]), f"{stack.robot}: {driver.last_failure}"
        assert driver.retreat(), f"{stack.robot}: {driver.last_failure}"
