"""MoveGroup: MoveGroupCommander's API over the sixdof move_group node (moveit_commander's MoveGroupCommander
is this class under its upstream constructor signature)."""

from __future__ import annotations

import math
import numbers
import threading
import time
from collections.abc import Mapping, Sequence

import numpy as np
import rospy
from geometry_msgs.msg import Pose, PoseStamped
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import (
    Constraints,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    MotionPlanRequest,
    MoveGroupAction,
    MoveItErrorCodes,
    RobotState,
    RobotTrajectory,
)
from sixdof_msgs.srv import (
    GetCartesianPath,
    GetMotionPlan,
    GetPositionFK,
    GetPositionIK,
    RetimeTrajectory,
    RetimeTrajectoryRequest,
)

from ._ros import (
    SERVICE_TIMEOUT,
    ActionClient,
    JointStateMonitor,
    ServerWaiter,
    call_service,
    load_robot_model,
    require_node,
    resolve,
    wait_for_done,
)
from .exceptions import MoveItCommanderException, SixdofCommanderError
from .goals import GoalBuilder, check_number, check_scaling_factor, pose_stamped_from_target
from .kinematics import bounded, iterative_parabolic_times, jacobian, random_value
from .planning_scene import PlanningScene
from .robot_model import RobotDescription, SemanticDescription, resolve_group
from .transforms import rpy_from_quaternion

SERVICES = (
    "plan_kinematic_path",
    "compute_fk",
    "compute_cartesian_path",
    "get_planning_scene",
    "apply_planning_scene",
    "get_robot_model",
)
RETIME_ALGORITHMS = ("iterative_time_parameterization", "time_optimal_trajectory_generation")


def error_code(value: int, message: str, source: str = "sixdof_commander") -> MoveItErrorCodes:
    """A MoveItErrorCodes message."""
    code = MoveItErrorCodes()
    code.val = value
    code.message = message
    code.source = source
    return code


def _refuse(method: str, why: str) -> MoveItCommanderException:
    call = method if "(" in method else f"{method}()"
    return SixdofCommanderError(f"{call} is not available on sixdof: {why}")


class MoveGroup:
    """Plans and moves one planning group (MoveGroupCommander's method names and semantics).

    Targets and parameters are kept here; plan() calls the plan_kinematic_path service, go() the
    move_group action (plan and execute), execute() the execute_trajectory action.
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
        self._ns = ns
        waiter = ServerWaiter(wait_for_servers)
        self._move_action = ActionClient(resolve(ns, "move_group"), MoveGroupAction)
        self._execute_action = ActionClient(resolve(ns, "execute_trajectory"), ExecuteTrajectoryAction)
        waiter.action(self._move_action, resolve(ns, "move_group"))
        waiter.action(self._execute_action, resolve(ns, "execute_trajectory"))
        for name in SERVICES:
            waiter.service(resolve(ns, name))
        waiter.check(f"MoveGroup('{group_name}')")
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
        self._last_error = error_code(MoveItErrorCodes.SUCCESS, "")
        self._support_surface = ""

        self._plan_service = rospy.ServiceProxy(resolve(ns, "plan_kinematic_path"), GetMotionPlan)
        self._fk_service = rospy.ServiceProxy(resolve(ns, "compute_fk"), GetPositionFK)
        self._ik_service = rospy.ServiceProxy(resolve(ns, "compute_ik"), GetPositionIK)
        self._cartesian_service = rospy.ServiceProxy(resolve(ns, "compute_cartesian_path"), GetCartesianPath)
        self._retime_service = rospy.ServiceProxy(resolve(ns, "retime_trajectory"), RetimeTrajectory)
        self._joint_states = JointStateMonitor(resolve(ns, "joint_states"))
        self._scene = PlanningScene(ns, wait_for_servers=wait_for_servers, robot_description=robot_description)
        self._rng = np.random.default_rng()

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
        raise _refuse("get_interface_description", "move_group offers one planning pipeline (OMPL) and no query of it")

    @property
    def last_error(self) -> MoveItErrorCodes:
        """The error code of the last plan/go/execute/compute_cartesian_path call."""
        return self._last_error

    # Targets -----------------------------------------------------------------------------------------
    def _use_link(self, end_effector_link: str) -> None:
        if end_effector_link:
            self.set_end_effector_link(end_effector_link)

    def set_pose_target(self, pose: object, end_effector_link: str = "") -> None:
        """Target pose of the end-effector link: [x, y, z, roll, pitch, yaw] (radians, fixed axes),
        [x, y, z, qx, qy, qz, qw] (unit quaternion), a Pose or a PoseStamped (planning frame if no frame)."""
        self._use_link(end_effector_link)
        self._goal.set_pose_target(pose)

    def set_pose_targets(self, poses: Sequence[object], end_effector_link: str = "") -> None:
        """Several pose targets of the end-effector link: the plan reaches any one of them."""
        self._use_link(end_effector_link)
        self._goal.set_pose_targets(poses)

    def set_position_target(self, xyz: Sequence[float], end_effector_link: str = "") -> None:
        """Target position of the end-effector link, orientation free."""
        self._use_link(end_effector_link)
        self._goal.set_position_target(xyz)

    def set_rpy_target(self, rpy: Sequence[float], end_effector_link: str = "") -> None:
        """Refused: orientation-only goals (any position) are not supported by sixdof's move_group."""
        raise _refuse("set_rpy_target", "move_group does not plan to orientation-only goals; use set_pose_target")

    def set_orientation_target(self, q: Sequence[float], end_effector_link: str = "") -> None:
        """Refused: orientation-only goals (any position) are not supported by sixdof's move_group."""
        raise _refuse(
            "set_orientation_target", "move_group does not plan to orientation-only goals; use set_pose_target"
        )

    def shift_pose_target(self, axis: int, value: float, end_effector_link: str = "") -> None:
        """Pose target = the current pose with `value` added to one axis (0..5: x, y, z, roll, pitch, yaw)."""
        if isinstance(axis, bool) or not isinstance(axis, numbers.Integral) or not 0 <= axis <= 5:
            raise SixdofCommanderError(f"shift_pose_target: axis must be an integer 0..5 (x y z r p y), got {axis!r}")
        current = self.get_current_pose(end_effector_link)
        p, q = current.pose.position, current.pose.orientation
        values = [p.x, p.y, p.z, *rpy_from_quaternion((q.x, q.y, q.z, q.w))]
        values[axis] += check_number(value, "shift_pose_target value")
        target = PoseStamped()
        target.header.frame_id = current.header.frame_id
        target.pose = pose_stamped_from_target(values, current.header.frame_id).pose
        self.set_pose_target(target, end_effector_link)

    def set_joint_value_target(self, arg1: object, arg2: object = None, arg3: object = None) -> None:
        """Joint target, in MoveGroupCommander's forms:
        a list/tuple/ndarray in get_active_joints() order; a dict name -> value (other joints keep their current
        values); a JointState (names and positions of the same length); (joint name, value); a RobotState; or a
        Pose/PoseStamped solved by IK for the end-effector link (arg2/arg3: end-effector link name and/or
        `approx`). Values outside the URDF limits raise SixdofCommanderError."""
        if isinstance(arg1, RobotState):
            self._no_extra_arguments(arg2, arg3)
            self._set_joint_state_target(arg1.joint_state, "RobotState.joint_state")
        elif isinstance(arg1, JointState):
            self._no_extra_arguments(arg2, arg3)
            self._set_joint_state_target(arg1, "JointState")
        elif isinstance(arg1, str):
            if arg2 is None:
                raise SixdofCommanderError(
                    f"set_joint_value_target('{arg1}'): a joint value is expected after the joint name"
                )
            self._no_extra_arguments(arg3)
            self._set_joint_dict({arg1: arg2})
        elif isinstance(arg1, Pose | PoseStamped):
            link, approx = self._ik_options(arg2, arg3)
            self._set_joint_dict(self._solve_ik(arg1, link, approx))
        elif isinstance(arg1, Mapping):
            self._no_extra_arguments(arg2, arg3)
            self._set_joint_dict(arg1)
        else:
            self._no_extra_arguments(arg2, arg3)
            self._goal.set_joint_value_target(arg1)

    @staticmethod
    def _no_extra_arguments(*args: object) -> None:
        if any(a is not None for a in args):
            raise SixdofCommanderError("set_joint_value_target: too many arguments for this target form")

    def _set_joint_dict(self, values: Mapping[str, float]) -> None:
        current = None
        if set(values) != set(self._group.joint_names):
            unknown = sorted(str(k) for k in values if k not in self._group.joint_names)
            current = None if unknown else self._joint_states.positions(self._group.joint_names)
        self._goal.set_joint_value_target(values, current)

    def _set_joint_state_target(self, msg: JointState, what: str) -> None:
        if len(msg.name) != len(msg.position):
            raise SixdofCommanderError(
                f"{what} has {len(msg.name)} names but {len(msg.position)} positions: they must match"
            )
        values = dict(zip(msg.name, msg.position, strict=True))
        # Joints of other groups in a whole-robot state are not part of this target (as MoveIt ignores them).
        mine = {name: value for name, value in values.items() if name in self._group.joint_names}
        if not mine:
            raise SixdofCommanderError(
                f"{what} names none of the joints of group '{self._group.name}' {self._group.joint_names}"
            )
        self._set_joint_dict(mine)

    def _ik_options(self, arg2: object, arg3: object) -> tuple[str, bool]:
        link, approx = "", False
        for arg in (arg2, arg3):
            if arg is None:
                continue
            if isinstance(arg, bool):
                approx = arg
            elif isinstance(arg, str):
                link = arg
            else:
                raise SixdofCommanderError(
                    f"set_joint_value_target(pose, ...): expected an end-effector link name or approx (bool), "
                    f"got {type(arg).__name__}"
                )
        return link, approx

    def _solve_ik(self, pose: Pose | PoseStamped, link: str, approx: bool) -> dict[str, float]:
        link = link or self._goal.end_effector_link
        if link not in self._urdf.links:
            raise SixdofCommanderError(f"set_joint_value_target: link '{link}' is not a link of the robot")
        request = GetPositionIK._request_class()
        request.ik_request.group_name = self._group.name
        request.ik_request.robot_state.is_diff = True
        request.ik_request.ik_link_name = link
        request.ik_request.pose_stamped = pose_stamped_from_target(pose, self._goal.pose_reference_frame)
        try:
            response = call_service(self._ik_service, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"set_joint_value_target: compute_ik call failed: {err}") from err
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            # An exact solution is also the best approximate one; the solvers have no approximate mode beyond it.
            hint = " (approximate IK: the solvers return exact solutions only)" if approx else ""
            raise SixdofCommanderError(
                f"set_joint_value_target: no IK solution for link '{link}': {response.error_code.message}{hint}"
            )
        solution = dict(zip(response.solution.joint_state.name, response.solution.joint_state.position, strict=False))
        return {name: solution[name] for name in self._group.joint_names if name in solution}

    def set_named_target(self, name: str) -> None:
        """Joint target from an SRDF group state (or a remembered one) of this group."""
        self._goal.set_named_target(name)

    def get_named_targets(self) -> list[str]:
        """Names of the group's SRDF states and remembered joint values."""
        return self._goal.named_targets()

    def get_named_target_values(self, target: str) -> dict[str, float]:
        """Joint values of a named target, by joint name."""
        return self._goal.named_target_values(target)

    def remember_joint_values(self, name: str, values: Sequence[float] | None = None) -> None:
        """Store joint values (default: the current ones) as a named target."""
        if values is None:
            values = self.get_current_joint_values()
        self._goal.remember_joint_values(name, values)

    def get_remembered_joint_values(self) -> dict[str, list[float]]:
        """Remembered joint values by name, each in get_active_joints() order."""
        return {name: [values[j] for j in self._group.joint_names] for name, values in self._goal.remembered.items()}

    def forget_joint_values(self, name: str) -> None:
        """Forget remembered joint values."""
        self._goal.forget_joint_values(name)

    def set_random_target(self) -> None:
        """A random joint target within the limits."""
        self.set_joint_value_target(self.get_random_joint_values())

    def get_joint_value_target(self) -> list[float]:
        """The joint target, in get_active_joints() order (empty without a joint target)."""
        target = self._goal.joint_target
        return [target[n] for n in self._group.joint_names] if target else []

    def get_pose_target(self) -> PoseStamped | None:
        """The pose target, or None."""
        return self._goal.pose_target

    def clear_pose_target(self, end_effector_link: str) -> None:
        """Forget the pose target of that end-effector link (this group has one pose target at a time)."""
        if end_effector_link in ("", self._goal.end_effector_link):
            self._goal.clear_pose_targets()

    def clear_pose_targets(self) -> None:
        """Forget the pose/position target."""
        self._goal.clear_pose_targets()

    def set_start_state(self, msg: RobotState) -> None:
        """Plan from this state instead of the current one."""
        if not isinstance(msg, RobotState):
            raise SixdofCommanderError(f"set_start_state needs a RobotState, got {type(msg).__name__}")
        if len(msg.joint_state.name) != len(msg.joint_state.position):
            raise SixdofCommanderError(
                f"start state has {len(msg.joint_state.name)} joint names but {len(msg.joint_state.position)} "
                "positions: they must match"
            )
        self._goal.start_state = msg

    def set_start_state_to_current_state(self) -> None:
        """Plan from the planner's current state (the default)."""
        self._goal.start_state = None

    # Parameters --------------------------------------------------------------------------------------
    def set_max_velocity_scaling_factor(self, value: float) -> None:
        """Scale the joints' maximum velocities by value in (0, 1]."""
        self._goal.set_max_velocity_scaling_factor(value)

    def set_max_acceleration_scaling_factor(self, value: float) -> None:
        """Scale the joints' maximum accelerations by value in (0, 1]."""
        self._goal.set_max_acceleration_scaling_factor(value)

    def set_planning_time(self, seconds: float) -> None:
        """Time allowed to plan, seconds (> 0; default 5)."""
        self._goal.set_planning_time(seconds)

    def get_planning_time(self) -> float:
        """Time allowed to plan, seconds."""
        return self._goal.planning_time

    def set_num_planning_attempts(self, num_planning_attempts: int) -> None:
        """Number of planning attempts (>= 1; the shortest solution wins)."""
        self._goal.set_num_planning_attempts(num_planning_attempts)

    def set_planner_id(self, planner_id: str) -> None:
        """The planner to use, e.g. 'RRTConnect' ('' for the node's default)."""
        self._goal.planner_id = str(planner_id)

    def get_planner_id(self) -> str:
        """The planner requested ('' for the node's default)."""
        return self._goal.planner_id

    def set_planning_pipeline_id(self, planning_pipeline: str) -> None:
        """The planning pipeline: move_group has one, 'ompl' ('' means it too); others raise."""
        if planning_pipeline not in ("", "ompl"):
            raise SixdofCommanderError(
                f"planning pipeline '{planning_pipeline}' is not available: sixdof's move_group has one, 'ompl'"
            )

    def get_planning_pipeline_id(self) -> str:
        """The planning pipeline ('ompl', the only one)."""
        return "ompl"

    def set_goal_tolerance(self, value: float) -> None:
        """Set the joint, position and orientation goal tolerances at once."""
        self.set_goal_joint_tolerance(value)
        self.set_goal_position_tolerance(value)
        self.set_goal_orientation_tolerance(value)

    def set_goal_joint_tolerance(self, value: float) -> None:
        """Joint goal tolerance, radians or metres (default 1e-4)."""
        self._goal.set_goal_joint_tolerance(value)

    def set_goal_position_tolerance(self, value: float) -> None:
        """Position goal tolerance, metres (default 1e-4)."""
        self._goal.set_goal_position_tolerance(value)

    def set_goal_orientation_tolerance(self, value: float) -> None:
        """Orientation goal tolerance about each axis, radians (default 1e-3)."""
        self._goal.set_goal_orientation_tolerance(value)

    def get_goal_tolerance(self) -> tuple[float, float, float]:
        """(joint, position, orientation) goal tolerances."""
        g = self._goal
        return (g.goal_joint_tolerance, g.goal_position_tolerance, g.goal_orientation_tolerance)

    def get_goal_joint_tolerance(self) -> float:
        """Joint goal tolerance."""
        return self._goal.goal_joint_tolerance

    def get_goal_position_tolerance(self) -> float:
        """Position goal tolerance (radius of a sphere around the target, metres)."""
        return self._goal.goal_position_tolerance

    def get_goal_orientation_tolerance(self) -> float:
        """Orientation goal tolerance (about each axis, radians)."""
        return self._goal.goal_orientation_tolerance

    def allow_looking(self, value: bool) -> None:
        """Looking around (moving sensors to clear unknown space) is not supported: only False is accepted."""
        if value:
            raise _refuse("allow_looking(True)", "move_group has no sensor to look around with")

    def allow_replanning(self, value: bool) -> None:
        """Replanning after an environment change during execution is not supported: only False is accepted."""
        if value:
            raise _refuse(
                "allow_replanning(True)",
                "move_group does not replan during execution; a failed go() returns False and can be retried",
            )

    def get_known_constraints(self) -> list[str]:
        """Names of stored constraints: none (MoveIt reads them from its warehouse database; there is none)."""
        return []

    def get_path_constraints(self) -> Constraints:
        """The path constraints: always empty (move_group plans without path constraints)."""
        return Constraints()

    def set_path_constraints(self, value: Constraints | str | None) -> None:
        """None or an empty Constraints clears them; any real path constraint raises (move_group's planner does
        not support path constraints: a plan would silently ignore them)."""
        if value is None or (isinstance(value, Constraints) and not _has_constraints(value)):
            return
        raise _refuse("set_path_constraints", "move_group's planner does not support path constraints")

    def clear_path_constraints(self) -> None:
        """No path constraints (the only setting move_group supports)."""

    def get_trajectory_constraints(self) -> Constraints:
        """The trajectory constraints: always empty."""
        return Constraints()

    def set_trajectory_constraints(self, value: Constraints | None) -> None:
        """None or an empty Constraints; anything else raises (not supported by move_group)."""
        if value is None or (isinstance(value, Constraints) and not _has_constraints(value)):
            return
        raise _refuse("set_trajectory_constraints", "move_group's planner does not support trajectory constraints")

    def clear_trajectory_constraints(self) -> None:
        """No trajectory constraints (the only setting move_group supports)."""

    def set_constraints_database(self, host: str, port: int) -> None:
        """Refused: there is no constraints warehouse."""
        raise _refuse("set_constraints_database", "there is no warehouse database of constraints")

    def set_workspace(self, ws: Sequence[float]) -> None:
        """[] (no workspace), [minX, minY, maxX, maxY] or [minX, minY, minZ, maxX, maxY, maxZ]. As in MoveIt it bounds
        only the position of a floating or planar base joint; a robot with a fixed base has none, so it has no
        effect there. Robots with such joints raise (sixdof does not plan for them)."""
        if isinstance(ws, str) or not isinstance(ws, Sequence | np.ndarray) or len(ws) not in (0, 4, 6):
            raise SixdofCommanderError(
                f"set_workspace needs [], [minX, minY, maxX, maxY] or [minX, minY, minZ, maxX, maxY, maxZ], got {ws!r}"
            )
        values = [check_number(v, f"workspace element {i}") for i, v in enumerate(ws)]
        half = len(values) // 2
        if any(values[i] > values[i + half] for i in range(half)):
            raise SixdofCommanderError(f"set_workspace: a minimum exceeds its maximum in {values}")
        mobile = [j.name for j in self._urdf.joints.values() if j.type in ("floating", "planar")]
        if values and mobile:
            raise _refuse("set_workspace", f"the robot's base joints {mobile} are not planned by sixdof")

    def set_support_surface_name(self, value: str) -> None:
        """The support surface of pick/place (MoveIt uses it only there). Stored and reported by
        get_support_surface_name(); pick() and place() themselves are refused on sixdof."""
        if not isinstance(value, str):
            raise SixdofCommanderError(f"support surface name must be a string, got {value!r}")
        self._support_surface = value

    def get_support_surface_name(self) -> str:
        """The support surface name set (sixdof extension, for symmetry)."""
        return self._support_surface

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
        request = self._goal.motion_plan_request()
        start = time.monotonic()
        try:
            timeout = request.allowed_planning_time * max(request.num_planning_attempts, 1) + SERVICE_TIMEOUT
            response = call_service(self._plan_service, request, timeout).motion_plan_response
        except (rospy.ServiceException, rospy.ROSException) as err:
            self._last_error = error_code(MoveItErrorCodes.COMMUNICATION_FAILURE, f"plan_kinematic_path: {err}")
            return False, RobotTrajectory(), time.monotonic() - start, self._last_error
        self._last_error = response.error_code
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
        return self._run_action(self._move_action, self._goal.move_group_goal(), "move_group", wait)

    def execute(self, plan_msg: RobotTrajectory, wait: bool = True) -> bool:
        """Execute a planned trajectory (execute_trajectory action). Without wait, returns once sent."""
        if not isinstance(plan_msg, RobotTrajectory):
            raise SixdofCommanderError(f"execute() needs a sixdof_msgs/RobotTrajectory, got {type(plan_msg).__name__}")
        if not plan_msg.joint_trajectory.points:
            raise SixdofCommanderError("execute() got an empty trajectory (did planning fail?)")
        goal = ExecuteTrajectoryGoal()
        goal.trajectory = plan_msg
        return self._run_action(self._execute_action, goal, "execute_trajectory", wait)

    def _run_action(self, client: ActionClient, goal: object, name: str, wait: bool) -> bool:
        done = threading.Event()
        client.send_goal(goal, done_cb=lambda _state, _result: done.set())
        if not wait:
            self._last_error = error_code(MoveItErrorCodes.SUCCESS, f"{name} goal sent")
            return True
        reason = wait_for_done(client, done)
        if reason:
            client.stop_tracking_goal()
            self._last_error = error_code(MoveItErrorCodes.COMMUNICATION_FAILURE, f"{name}: {reason}")
            rospy.logerr(self._last_error.message)
            return False
        result = client.get_result()
        if result is None:
            self._last_error = error_code(
                MoveItErrorCodes.COMMUNICATION_FAILURE, f"{name}: no result (goal status {client.get_state()})"
            )
            return False
        self._last_error = result.error_code
        return result.error_code.val == MoveItErrorCodes.SUCCESS

    def stop(self) -> None:
        """Stop any motion this group's node is planning or executing."""
        self._move_action.cancel_all_goals()
        self._execute_action.cancel_all_goals()

    def pick(self, object_name: str, grasp: object = (), plan_only: bool = False) -> None:
        """Refused: there is no pick action; sixdof_commander.ArmDriver.pick(object) picks simulator objects."""
        raise _refuse("pick", "move_group has no pick action; use sixdof_commander.ArmDriver.pick(object_name)")

    def place(self, object_name: str, location: object = None, plan_only: bool = False) -> None:
        """Refused: there is no place action; sixdof_commander.ArmDriver.place(position) places the held object."""
        raise _refuse("place", "move_group has no place action; use sixdof_commander.ArmDriver.place([x, y])")

    # Current state -----------------------------------------------------------------------------------
    def get_current_joint_values(self) -> list[float]:
        """Current positions of the group's joints from joint_states, in get_active_joints() order."""
        positions = self._joint_states.positions(self._group.joint_names)
        return [positions[n] for n in self._group.joint_names]

    def get_current_state(self) -> RobotState:
        """The current joint positions of the whole robot, as a RobotState. A mimic joint's value is computed
        from its source joint, as MoveIt's RobotState does: joint_states reports what a physical mimic coupling
        measures, which may lag its source (a parallel gripper squeezing an object)."""
        measured = self._joint_states.joint_state()
        values = dict(zip(measured.name, measured.position, strict=True))
        state = RobotState()
        for name, position in values.items():
            joint = self._urdf.joints.get(name)
            if joint is not None and joint.mimic is not None and joint.mimic in values:
                position = joint.mimic_multiplier * values[joint.mimic] + joint.mimic_offset
            state.joint_state.name.append(name)
            state.joint_state.position.append(position)
        return state

    def get_current_state_bounded(self) -> RobotState:
        """The current state with every joint value moved into its limits."""
        return self.enforce_bounds(self.get_current_state())

    def _fk(self, link: str, state: RobotState) -> PoseStamped:
        if link not in self._urdf.links:
            raise SixdofCommanderError(f"link '{link}' is not a link of the robot")
        request = GetPositionFK._request_class()
        request.header.frame_id = self._planning_frame
        request.fk_link_names = [link]
        request.robot_state = state
        try:
            response = call_service(self._fk_service, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"compute_fk call failed: {err}") from err
        if response.error_code.val != MoveItErrorCodes.SUCCESS or len(response.pose_stamped) != 1:
            raise SixdofCommanderError(
                f"compute_fk failed for link '{link}': {response.error_code.val} {response.error_code.message}"
            )
        return response.pose_stamped[0]

    def get_current_pose(self, end_effector_link: str = "") -> PoseStamped:
        """Pose of the end-effector link (or the given link) in the planning frame (compute_fk service)."""
        return self._fk(end_effector_link or self._goal.end_effector_link, self.get_current_state())

    def get_current_rpy(self, end_effector_link: str = "") -> list[float]:
        """[roll, pitch, yaw] (fixed axes, radians) of the end-effector link in the planning frame."""
        q = self.get_current_pose(end_effector_link).pose.orientation
        return list(rpy_from_quaternion((q.x, q.y, q.z, q.w)))

    def get_random_joint_values(self) -> list[float]:
        """Uniformly random joint values within the limits, in get_active_joints() order."""
        return [random_value(joint, self._rng) for joint in self._group.joints]

    def get_random_pose(self, end_effector_link: str = "") -> PoseStamped:
        """Pose of the end-effector link at random joint values (compute_fk), in the planning frame."""
        state = RobotState()
        state.is_diff = True
        state.joint_state.name = self._group.joint_names
        state.joint_state.position = self.get_random_joint_values()
        return self._fk(end_effector_link or self._goal.end_effector_link, state)

    def get_jacobian_matrix(
        self, joint_values: Sequence[float], reference_point: Sequence[float] | None = None
    ) -> np.ndarray:
        """Jacobian (numpy 6 x n: linear rows then angular, planning frame) of the group's tip link (at
        reference_point in its frame, default its origin) at joint_values (get_active_joints() order)."""
        names = self._group.joint_names
        if isinstance(joint_values, str) or not isinstance(joint_values, Sequence | np.ndarray):
            raise SixdofCommanderError(f"get_jacobian_matrix: joint_values must be a list, got {joint_values!r}")
        if len(joint_values) != len(names):
            raise SixdofCommanderError(
                f"get_jacobian_matrix: joint_values must have {len(names)} values {names}, got {len(joint_values)}"
            )
        point = [0.0, 0.0, 0.0] if reference_point is None else list(reference_point)
        if len(point) != 3:
            raise SixdofCommanderError(f"get_jacobian_matrix: reference_point must be [x, y, z], got {point!r}")
        values = {n: check_number(v, f"joint value of '{n}'") for n, v in zip(names, joint_values, strict=True)}
        point = [check_number(v, f"reference_point element {i}") for i, v in enumerate(point)]
        return jacobian(self._urdf, self._group, values, point)

    def enforce_bounds(self, robot_state_msg: RobotState) -> RobotState:
        """A copy of the RobotState with every known joint's value moved into its limits."""
        if not isinstance(robot_state_msg, RobotState):
            raise SixdofCommanderError(f"enforce_bounds needs a RobotState, got {type(robot_state_msg).__name__}")
        source = robot_state_msg.joint_state
        if len(source.name) != len(source.position):
            raise SixdofCommanderError(
                f"enforce_bounds: {len(source.name)} joint names but {len(source.position)} positions"
            )
        result = RobotState()
        result.is_diff = robot_state_msg.is_diff
        result.attached_collision_objects = list(robot_state_msg.attached_collision_objects)
        result.joint_state.header = source.header
        result.joint_state.name = list(source.name)
        result.joint_state.velocity = list(source.velocity)
        result.joint_state.effort = list(source.effort)
        joints = self._urdf.joints
        result.joint_state.position = [
            bounded(joints[n], p) if n in joints else p for n, p in zip(source.name, source.position, strict=True)
        ]
        return result

    # Cartesian paths ---------------------------------------------------------------------------------
    def compute_cartesian_path(
        self,
        waypoints: Sequence[Pose],
        eef_step: float,
        *args: object,
        path_constraints: Constraints | None = None,
        **kwargs: object,
    ) -> tuple[RobotTrajectory, float]:
        """Straight-line path of the end-effector link through waypoints (Poses in the pose reference frame),
        interpolated every eef_step metres: (trajectory, fraction of the path achieved; -1 on error).

        Both MoveIt signatures: (waypoints, eef_step, avoid_collisions=True, path_constraints=None) (1.1.15 on) and
        (waypoints, eef_step, jump_threshold, avoid_collisions=True) (before): a number (not a bool) in third
        place is the jump threshold (0 = no jump check)."""
        jump_threshold, avoid_collisions = _cartesian_arguments(args, kwargs)
        if path_constraints is not None and _has_constraints(path_constraints):
            raise _refuse("compute_cartesian_path(path_constraints=...)", "path constraints are not supported")
        request = self._goal.cartesian_path_request(waypoints, eef_step, jump_threshold, avoid_collisions)
        try:
            response = call_service(self._cartesian_service, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            self._last_error = error_code(MoveItErrorCodes.COMMUNICATION_FAILURE, f"compute_cartesian_path: {err}")
            return RobotTrajectory(), -1.0
        self._last_error = response.error_code
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            return response.solution, -1.0
        return response.solution, response.fraction

    # Time parameterization ---------------------------------------------------------------------------
    def retime_trajectory(
        self,
        ref_state_in: RobotState,
        traj_in: RobotTrajectory,
        velocity_scaling_factor: float = 1.0,
        acceleration_scaling_factor: float = 1.0,
        algorithm: str = "iterative_time_parameterization",
    ) -> RobotTrajectory:
        """The trajectory's path re-timed for these scaling factors of the joint limits (robot_description_planning,
        else the URDF's velocity limits), starting and ending at rest. 'iterative_time_parameterization' is
        computed here; 'time_optimal_trajectory_generation' is move_group's time-optimal parameterization (the one
        every plan gets), through its retime_trajectory service. A failure raises SixdofCommanderError."""
        if algorithm not in RETIME_ALGORITHMS:
            raise SixdofCommanderError(
                f"retime_trajectory: unknown algorithm '{algorithm}'; known: {list(RETIME_ALGORITHMS)}"
            )
        if not isinstance(ref_state_in, RobotState) or not isinstance(traj_in, RobotTrajectory):
            raise SixdofCommanderError("retime_trajectory needs a RobotState and a RobotTrajectory")
        velocity = check_scaling_factor(velocity_scaling_factor, "velocity_scaling_factor")
        acceleration = check_scaling_factor(acceleration_scaling_factor, "acceleration_scaling_factor")
        if algorithm == "time_optimal_trajectory_generation":
            return self._retime_time_optimal(traj_in, velocity, acceleration)
        names = list(traj_in.joint_trajectory.joint_names)
        points = traj_in.joint_trajectory.points
        if not names or not points:
            raise SixdofCommanderError("retime_trajectory: the trajectory has no joints or no points")
        for i, point in enumerate(points):
            if len(point.positions) != len(names):
                raise SixdofCommanderError(
                    f"retime_trajectory: point {i} has {len(point.positions)} positions for {len(names)} joints"
                )
        path = np.array([[check_number(v, f"point {i} position") for v in p.positions] for i, p in enumerate(points)])
        max_velocity, max_acceleration = self._joint_limits(names)
        times, velocities, accelerations = iterative_parabolic_times(
            path, max_velocity * velocity, max_acceleration * acceleration
        )
        result = RobotTrajectory()
        result.joint_trajectory.header = traj_in.joint_trajectory.header
        result.joint_trajectory.joint_names = names
        for t, q, v, a in zip(times, path, velocities, accelerations, strict=True):
            result.joint_trajectory.points.append(
                JointTrajectoryPoint(
                    positions=list(q),
                    velocities=list(v),
                    accelerations=list(a),
                    time_from_start=rospy.Duration.from_sec(float(t)),
                )
            )
        return result

    def _retime_time_optimal(
        self, trajectory: RobotTrajectory, velocity: float, acceleration: float
    ) -> RobotTrajectory:
        request = RetimeTrajectoryRequest(
            trajectory=trajectory, velocity_scaling_factor=velocity, acceleration_scaling_factor=acceleration
        )
        try:
            response = call_service(self._retime_service, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(
                f"retime_trajectory: move_group's retime_trajectory service failed: {err}"
            ) from err
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            raise SixdofCommanderError(f"retime_trajectory: {response.error_code.message}")
        return response.trajectory

    def _joint_limits(self, names: list[str]) -> tuple[np.ndarray, np.ndarray]:
        """Velocity and acceleration limits of the joints, as move_group reads them (MoveIt's joint_limits)."""
        param = resolve(self._ns, "robot_description_planning/joint_limits")
        limits = rospy.get_param(param, {})
        velocities, accelerations = [], []
        for name in names:
            if name not in self._urdf.joints:
                raise SixdofCommanderError(f"retime_trajectory: '{name}' is not a joint of the robot")
            entry = limits.get(name, {}) if isinstance(limits, dict) else {}
            velocity = entry.get("max_velocity") if entry.get("has_velocity_limits", True) else None
            velocity = velocity if velocity is not None else self._urdf.joints[name].velocity
            acceleration = entry.get("max_acceleration") if entry.get("has_acceleration_limits", False) else None
            for value, what in ((velocity, "velocity"), (acceleration, "acceleration")):
                if value is None or not math.isfinite(float(value)) or float(value) <= 0.0:
                    raise SixdofCommanderError(
                        f"retime_trajectory: joint '{name}' has no {what} limit in "
                        f"'{rospy.resolve_name(param)}' (or the URDF)"
                    )
            velocities.append(float(velocity))
            accelerations.append(float(acceleration))
        return np.array(velocities), np.array(accelerations)

    # Attached objects --------------------------------------------------------------------------------
    def attach_object(self, object_name: str, link_name: str = "", touch_links: Sequence[str] | None = None) -> bool:
        """Attach a planning-scene object to link_name (default: the end-effector link)."""
        return self._scene.attach_object(object_name, link_name or self._goal.end_effector_link, touch_links or None)

    def detach_object(self, name: str = "") -> bool:
        """Detach an attached object (all of them with no name) back into the world."""
        return self._scene.detach_object(name)


def _has_constraints(value: Constraints) -> bool:
    return bool(value.joint_constraints or value.position_constraints or value.orientation_constraints)


def _cartesian_arguments(args: tuple[object, ...], kwargs: dict[str, object]) -> tuple[float, bool]:
    """(jump_threshold, avoid_collisions) from compute_cartesian_path's positional/keyword arguments after eef_step."""
    unknown = sorted(set(kwargs) - {"jump_threshold", "avoid_collisions"})
    if unknown:
        raise SixdofCommanderError(f"compute_cartesian_path: unexpected keyword arguments {unknown}")
    jump_threshold: object = kwargs.get("jump_threshold", 0.0)
    avoid_collisions: object = kwargs.get("avoid_collisions", True)
    rest = list(args)
    if rest and not isinstance(rest[0], bool) and isinstance(rest[0], numbers.Real):
        if "jump_threshold" in kwargs:
            raise SixdofCommanderError("compute_cartesian_path: jump_threshold given twice")
        jump_threshold = rest.pop(0)
    if rest:
        if "avoid_collisions" in kwargs:
            raise SixdofCommanderError("compute_cartesian_path: avoid_collisions given twice")
        avoid_collisions = rest.pop(0)
    if rest:
        raise SixdofCommanderError(f"compute_cartesian_path: too many positional arguments ({len(args) + 2})")
    return jump_threshold, avoid_collisions
