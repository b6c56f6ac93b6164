"""What the nodes that fill move_group's planning scene share (sixdof_bringup's scene_mirror, sixdof_perception's
perception_node).

The robot model comes from move_group's `get_robot_model` (sixdof_commander's query_robot_model: the core's
RobotModel is the project's only URDF/SRDF reader), the scene is read and changed through move_group's
get_planning_scene (the world objects and the attached ones) / apply_planning_scene (a refusal is logged in the
words of move_group's error report), and every wait for move_group is bounded: a node started without it exits
with one line naming the missing services instead of waiting forever.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Protocol

import rospy
import yaml
from moveit_msgs.msg import MoveItErrorCodes, PlanningScene, PlanningSceneComponents
from moveit_msgs.srv import ApplyPlanningScene, GetPlanningScene, GetPlanningSceneRequest

from ._ros import ServerWaiter, query_robot_model
from .error_reports import ErrorReports
from .exceptions import SixdofCommanderError
from .planning_scene import default_touch_links
from .robot_model import RobotDescription, SemanticDescription
from .scene_mirror import Updates

# Default of the nodes' ~wait_for_move_group: they start beside move_group, which may load for a while on a
# loaded machine; the bound only turns "move_group never came" into an error instead of a silent hang.
MOVE_GROUP_WAIT = 60.0


def number_param(name: str, default: float, minimum: float = 0.0, inclusive: bool = True) -> float:
    """A finite numeric parameter >= minimum (> minimum when not inclusive); ValueError naming it otherwise."""
    value = rospy.get_param(name, default)
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not math.isfinite(value)
        or value < minimum
        or (value == minimum and not inclusive)
    ):
        relation = ">=" if inclusive else ">"
        raise ValueError(f"parameter {rospy.resolve_name(name)} must be a number {relation} {minimum:g}, got {value!r}")
    return float(value)


@dataclass(frozen=True)
class SceneRobot:
    """The robot as move_group models it, for a node that fills the planning scene."""

    urdf: RobotDescription
    srdf: SemanticDescription
    planning_frame: str

    def touch_links(self, link: str) -> list[str]:
        """The links an object held by `link` may touch: the commander's default (the link, links fixed to it, its
        end effectors' links). move_group keeps those with collision geometry (a tcp frame touches nothing)."""
        return default_touch_links(self.urdf, self.srdf, link)


class MoveGroupScene:
    """move_group's robot model and planning-scene services, waited for under one bounded wall-clock wait."""

    def __init__(
        self, who: str, timeout: float, extra_services: Iterable[str] = (), collision_geometry: bool = False
    ) -> None:
        """Waits up to `timeout` s (0: forever) for get_robot_model, get_planning_scene, apply_planning_scene
        and `extra_services`; SixdofCommanderError names every one missing. With `collision_geometry` the robot
        model carries the links' collision shapes (RobotDescription.collision)."""
        services = ["get_robot_model", "get_planning_scene", "apply_planning_scene", *extra_services]
        waiter = ServerWaiter(timeout)
        for service in services:
            rospy.loginfo("%s: waiting for %s", who, rospy.resolve_name(service))
            waiter.service(service)
        waiter.check("needed services")
        self.who = who
        urdf, srdf = query_robot_model("", timeout, collision_geometry=collision_geometry)
        # move_group's model frame (the SRDF virtual joint's parent frame, else the root link).
        self.robot = SceneRobot(urdf=urdf, srdf=srdf, planning_frame=srdf.virtual_joint_parent or urdf.root_link)
        self._get_scene = rospy.ServiceProxy("get_planning_scene", GetPlanningScene)
        self._apply = rospy.ServiceProxy("apply_planning_scene", ApplyPlanningScene)
        self._reports = ErrorReports()

    def scene(self) -> PlanningScene:
        """The world objects (with their poses and shapes) and the attached objects of the current planning scene
        (get_planning_scene)."""
        request = GetPlanningSceneRequest()
        request.components.components = (
            PlanningSceneComponents.WORLD_OBJECT_GEOMETRY | PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
        )
        return self._get_scene(request).scene

    def apply(self, updates: Updates) -> None:
        """Sends a SceneMirror's updates as one planning-scene diff; a refusal is logged (the next cycle re-reads
        the scene and retries what is still different)."""
        if updates.empty():
            return
        diff = PlanningScene(is_diff=True)
        diff.robot_state.is_diff = True
        diff.world.collision_objects = updates.world_objects
        diff.robot_state.attached_collision_objects = updates.attached_objects
        response, outcome = self._reports.call(
            self._apply, diff, code=lambda r: MoveItErrorCodes.SUCCESS if r.success else 0
        )
        if response is None:
            raise rospy.ServiceException(outcome.message)
        if outcome.val != MoveItErrorCodes.SUCCESS:
            rospy.logwarn("%s: apply_planning_scene failed: %s", self.who, outcome)


class CyclingNode(Protocol):
    rate: float

    def cycle(self) -> None: ...


def spin(who: str, node: CyclingNode, transient: tuple[type[BaseException], ...] = ()) -> None:
    """Calls node.cycle() at most node.rate times per wall-clock second until shutdown.

    Wall clock, because the simulator may run free or be paused. Service and `transient` errors are logged
    (throttled) and the next cycle tries again.
    """
    period = 1.0 / node.rate
    errors = (rospy.ServiceException, rospy.ROSException, *transient)
    while not rospy.is_shutdown():
        start = time.monotonic()
        try:
            node.cycle()
        except errors as err:
            if rospy.is_shutdown():
                break
            rospy.logwarn_throttle(5.0, f"{who}: {err}")
        time.sleep(max(0.0, period - (time.monotonic() - start)))


def run(who: str, build: Callable[[], CyclingNode], transient: tuple[type[BaseException], ...] = ()) -> int:
    """A scene node's main: init as `who`, build the node (bad configuration or no move_group: one fatal line,
    exit code 1), then spin."""
    rospy.init_node(who)
    try:
        node = build()
    except (ValueError, KeyError, OSError, yaml.YAMLError, SixdofCommanderError) as err:
        rospy.logfatal("%s: %s", who, err)
        return 1
    except rospy.ROSInterruptException:
        return 0
    spin(who, node, transient)
    return 0

