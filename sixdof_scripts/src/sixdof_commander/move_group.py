"""MoveGroup: MoveGroupCommander's API over the sixdof move_group node (moveit_commander's MoveGroupCommander
is this class under its upstream constructor signature).

This module: construction, introspection, plan/go/execute/stop and attached objects. MoveGroup holds its request
builder (goals.py: targets and parameters, from which the requests are built), its connections to move_group
(move_group_clients.py) and the current joint values (state_monitor.py), and serves the rest of its methods from
parts that get these collaborators, one concept a module: targets.py, planning_options.py, path_constraints.py,
current_state.py, cartesian_path.py, retiming.py (served_by in move_group_base.py)."""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import rospy
from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import MotionPlanRequest, MoveItErrorCodes, RobotState, RobotTrajectory
from sensor_msgs.msg import JointState

from ._ros import load_robot_model, require_node, resolve
from .cartesian_path import CartesianPath
from .current_state import CurrentState
from .error_reports import CallError
from .exceptions import SixdofCommanderError
from .goals import GoalBuilder
from .kinematics import parameter_kinematics
from .move_group_base import MoveGroupContext, refuse, served_by
from .move_group_clients import MoveGroupClients
from .path_constraints import PathConstraints
from .planning_options import GOAL_SETTERS, PlanningOptions
from .planning_scene import PlanningScene
from .retiming import Retiming
from .robot_model import RobotDescription, SemanticDescription, resolve_group
from .state_monitor import StateMonitor
from .targets import Targets


@served_by(
    _goal=(GoalBuilder, GOAL_SETTERS),
    _targets=Targets,
    _options=PlanningOptions,
    _constraints=PathConstraints,
    _current=CurrentState,
    _cartesian=CartesianPath,
    _retiming=Retiming,
)
class MoveGroup:
    """Plans and moves one planning group (MoveGroupCommander's method names and semantics).

    Targets and parameters are kept in a GoalBuilder; plan() calls the plan_kinematic_path service, go() the
    move_group action (plan and execute), execute() the execute_trajectory action. This class holds the
    construction, introspection, planning and execution; the methods of the parts named above are served by
    the part kept in that attribute (MoveGroup.set_pose_target: Targets.set_pose_target of self._targets).
    """

    def __init__(
        self,
        group_name: str,
        ns: str = "",
        wait_for_servers: float = 5.0,
        robot_description: str = "robot_description",
    ) -> None:
        """Waits up to wait_for_servers seconds (0: forever) for the move_group node's services and actions
        (SixdofCommanderError names what is missing), then gets the robot model from it (get_robot_model)."""
        require_node()
        self._clients = MoveGroupClients(ns, wait_for_servers, f"MoveGroup('{group_name}')")
        self._urdf, self._srdf = load_robot_model(ns, robot_description, wait_for_servers)
        self._group = resolve_group(self._urdf, self._srdf, group_name)
        self._planning_frame = self._srdf.virtual_joint_parent or self._urdf.root_link
        self._goal = GoalBuilder(self._group, self._planning_frame)
        # MoveIt reads the default scaling from the joint-limits config (0.1 when absent).
        planning = resolve(ns, "robot_description_planning")
        for kind, setter in (
            ("velocity", self._goal.set_max_velocity_scaling_factor),
            ("acceleration", self._goal.set_max_acceleration_scaling_factor),
        ):
            param = f"{planning}/default_{kind}_scaling_factor"
            try:
                setter(rospy.get_param(param, 0.1))
            except SixdofCommanderError as err:
                raise SixdofCommanderError(f"parameter '{rospy.resolve_name(param)}': {err}") from None
        self._state = StateMonitor(resolve(ns, "joint_states"), self._urdf)
        self._scene = PlanningScene(ns, wait_for_servers=wait_for_servers, robot_description=robot_description)
        context = MoveGroupContext(
            ns,
            self._group,
            self._urdf,
            self._planning_frame,
            self._goal,
            self._clients,
            self._state,
            parameter_kinematics(ns),
        )
        self._options = PlanningOptions(context)
        self._constraints = PathConstraints(context)
        self._current = CurrentState(context)
        self._targets = Targets(context, self._current)
        self._cartesian = CartesianPath(context)
        self._retiming = Retiming(context)

    # Introspection -----------------------------------------------------------------------------------
    @property
    def robot_description(self) -> RobotDescription:
        """The robot's kinematic tree (move_group's model)."""
        return self._urdf

    @property
    def semantic_description(self) -> SemanticDescription:
        """The robot's groups, named states and end effectors (move_group's model)."""
        return self._srdf

    def get_name(self) -> str:
        """The group's name."""
        return self._group.name

    def get_active_joints(self) -> list[str]:
        """The group's active joints, in order."""
        return self._group.joint_names

    def get_joints(self) -> list[str]:
        """Every joint of the group (fixed and mimic ones included), as MoveIt lists them."""
        return [joint.name for joint in self._group.all_joints]

    def get_variable_count(self) -> int:
        """Number of variables of the group's state (one per active joint)."""
        return len(self._group.joints)

    def get_planning_frame(self) -> str:
        """The frame plans and poses are expressed in (the URDF root or the SRDF virtual joint's parent)."""
        return self._planning_frame

    def get_pose_reference_frame(self) -> str:
        """The frame of pose targets and waypoints given without one (default: the planning frame)."""
        return self._goal.pose_reference_frame

    def set_pose_reference_frame(self, reference_frame: str) -> None:
        """Frame (a link of the robot) of pose targets and waypoints given without one."""
        if reference_frame != self._planning_frame and reference_frame not in self._urdf.links:
            raise SixdofCommanderError(
                f"pose reference frame '{reference_frame}' is neither the planning frame nor a link of the robot"
            )
        self._goal.pose_reference_frame = reference_frame

    def has_end_effector_link(self) -> bool:
        """True when pose targets have a link to refer to."""
        return bool(self._goal.end_effector_link)

    def get_end_effector_link(self) -> str:
        """The link pose targets refer to (the SRDF end effector's parent link, else the group's tip)."""
        return self._goal.end_effector_link

    def set_end_effector_link(self, link_name: str) -> None:
        """Use another link for pose targets and current poses."""
        self._goal.set_end_effector_link(link_name, self._urdf.links)

    def get_interface_description(self) -> None:
        """Refused: sixdof's move_group has one planning pipeline and no plugin description service."""
        raise refuse("get_interface_description", "move_group offers one planning pipeline (OMPL) and no query of it")

    @property
    def last_error(self) -> CallError:
        """The outcome of the last plan/go/execute/compute_cartesian_path call: `val` (MoveItErrorCodes), `name`,
        and `message`, the words of a failure (move_group's error report or the action's status text; the code's
        name alone when move_group sent none)."""
        return self._clients.last_error

    # Planning and execution --------------------------------------------------------------------------
    def _set_target_from(self, joints: object, method: str) -> None:
        """The target forms plan(joints) and go(joints) accept, as MoveGroupCommander's."""
        if isinstance(joints, JointState | RobotState | Mapping):
            self.set_joint_value_target(joints)
        elif isinstance(joints, Pose | PoseStamped):
            self.set_pose_target(joints)
        elif isinstance(joints, str):
            if joints not in self.get_named_targets():
                raise SixdofCommanderError(
                    f"{method}(): unknown named target '{joints}' for group '{self._group.name}'; "
                    f"known: {self.get_named_targets()}"
                )
            self.set_named_target(joints)
        else:
            self.set_joint_value_target(joints)

    def construct_motion_plan_request(self) -> MotionPlanRequest:
        """The MotionPlanRequest plan() would send."""
        return self._goal.motion_plan_request()

    def plan(self, joints: object = None) -> tuple[bool, RobotTrajectory, float, MoveItErrorCodes]:
        """Plan to the target (or first set the target from `joints`, in any form go() accepts):
        (success, trajectory, planning_time, error_code)."""
        if joints is not None:
            self._set_target_from(joints, "plan")
        start = time.monotonic()
        answer = self._clients.plan(self._goal.motion_plan_request())
        if answer is None:
            return False, RobotTrajectory(), time.monotonic() - start, self._clients.last_error.code
        response = answer.motion_plan_response
        success = response.error_code.val == MoveItErrorCodes.SUCCESS
        return success, response.trajectory, response.planning_time, response.error_code

    def go(self, joints: object = None, wait: bool = True) -> bool:
        """Plan to the target and execute (move_group action). `joints` may set the target first: a list, tuple,
        ndarray or dict of joint values, a JointState, a Pose or PoseStamped, a remembered or SRDF state name;
        a bool there means `wait`. Without wait, returns once the goal is sent."""
        if isinstance(joints, bool):
            wait, joints = joints, None
        elif joints is not None:
            self._set_target_from(joints, "go")
        return self._clients.move(self._goal.move_group_goal(), wait)

    def execute(self, plan_msg: RobotTrajectory, wait: bool = True) -> bool:
        """Execute a planned trajectory (execute_trajectory action). Without wait, returns once sent."""
        if not isinstance(plan_msg, RobotTrajectory):
            raise SixdofCommanderError(f"execute() needs a moveit_msgs/RobotTrajectory, got {type(plan_msg).__name__}")
        if not plan_msg.joint_trajectory.points:
            raise SixdofCommanderError("execute() got an empty trajectory (did planning fail?)")
        return self._clients.execute(plan_msg, wait)

    def stop(self) -> None:
        """Stop any motion this group's node is planning or executing."""
        self._clients.stop()

    def pick(self, object_name: str, grasp: object = (), plan_only: bool = False) -> None:
        """Refused: there is no pick action; sixdof_commander.ArmDriver.pick(object) picks simulator objects."""
        raise refuse("pick", "move_group has no pick action; use sixdof_commander.ArmDriver.pick(object_name)")

    def place(self, object_name: str, location: object = None, plan_only: bool = False) -> None:
        """Refused: there is no place action; sixdof_commander.ArmDriver.place(position) places the held object."""
        raise refuse("place", "move_group has no place action; use sixdof_commander.ArmDriver.place([x, y])")

    # Attached objects --------------------------------------------------------------------------------
    def attach_object(self, object_name: str, link_name: str = "", touch_links: Sequence[str] | None = None) -> bool:
        """Attach a planning-scene object to link_name (default: the end-effector link)."""
        return self._scene.attach_object(object_name, link_name or self._goal.end_effector_link, touch_links or None)

    def detach_object(self, name: str = "") -> bool:
        """Detach an attached object (all of them with no name) back into the world."""
        return self._scene.detach_object(name)
