"""Targets and planning parameters of a group, turned into moveit_msgs requests as MoveIt's commander does.

Everything here is plain data and message construction: no ROS communication, so it is unit-testable.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence

import numpy as np
from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import (
    Constraints,
    JointConstraint,
    MotionPlanRequest,
    MoveGroupGoal,
    OrientationConstraint,
    PositionConstraint,
    RobotState,
    WorkspaceParameters,
)
from moveit_msgs.srv import GetCartesianPathRequest
from shape_msgs.msg import SolidPrimitive

from .exceptions import SixdofCommanderError
from .robot_model import Group
from .transforms import quaternion_from_rpy

QUATERNION_NORM_TOLERANCE = 1e-3
POSE_LIST_FIELDS_RPY = ("x", "y", "z", "roll", "pitch", "yaw")
POSE_LIST_FIELDS_QUAT = ("x", "y", "z", "qx", "qy", "qz", "qw")


def check_number(value: object, what: str) -> float:
    """value as a float; SixdofCommanderError when it is not a real number or not finite."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SixdofCommanderError(f"{what} must be a number, got {value!r}")
    result = float(value)
    if not math.isfinite(result):
        raise SixdofCommanderError(f"{what} must be finite, got {result}")
    return result


def check_positive(value: object, what: str) -> float:
    """value as a finite float > 0."""
    result = check_number(value, what)
    if result <= 0.0:
        raise SixdofCommanderError(f"{what} must be > 0, got {result}")
    return result


def check_scaling_factor(value: object, what: str) -> float:
    """A velocity/acceleration scaling factor: a finite float in (0, 1]."""
    result = check_number(value, what)
    if not 0.0 < result <= 1.0:
        raise SixdofCommanderError(f"{what} must be in (0, 1], got {result}")
    return result


def _check_sequence(values: object, what: str) -> list[object]:
    if isinstance(values, np.ndarray):
        return list(values.ravel()) if values.ndim == 1 else _raise_not_list(values, what)
    if isinstance(values, str | bytes) or not isinstance(values, Sequence):
        _raise_not_list(values, what)
    return list(values)


def _raise_not_list(values: object, what: str) -> list[object]:
    raise SixdofCommanderError(f"{what} must be a list of numbers, got {type(values).__name__}")


def normalized_quaternion(q: Sequence[float], what: str) -> tuple[float, float, float, float]:
    """The unit quaternion q (finite, norm within 1e-3 of 1), renormalised to norm 1."""
    norm = math.sqrt(sum(c * c for c in q))
    if abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE:
        raise SixdofCommanderError(
            f"{what} (x, y, z, w) = {tuple(q)} has norm {norm:.6g}; a unit quaternion is required "
            f"(norm within {QUATERNION_NORM_TOLERANCE} of 1)"
        )
    return (q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm)


def _checked_pose(pose: Pose, what: str) -> Pose:
    p, o = pose.position, pose.orientation
    for axis in ("x", "y", "z"):
        check_number(getattr(p, axis), f"{what} position.{axis}")
    q = [check_number(getattr(o, axis), f"{what} orientation.{axis}") for axis in ("x", "y", "z", "w")]
    x, y, z, w = normalized_quaternion(q, f"{what} orientation")
    result = Pose()
    result.position.x, result.position.y, result.position.z = p.x, p.y, p.z
    result.orientation.x, result.orientation.y, result.orientation.z, result.orientation.w = x, y, z, w
    return result


def pose_from_list(values: Sequence[float], what: str = "pose target") -> Pose:
    """Pose from [x, y, z, roll, pitch, yaw] (radians, fixed axes) or [x, y, z, qx, qy, qz, qw]."""
    items = _check_sequence(values, what)
    if len(items) not in (6, 7):
        raise SixdofCommanderError(
            f"{what} list must have 6 elements (x, y, z, roll, pitch, yaw) or 7 (x, y, z, qx, qy, qz, qw), "
            f"got {len(items)}"
        )
    names = POSE_LIST_FIELDS_RPY if len(items) == 6 else POSE_LIST_FIELDS_QUAT
    numbers_ = [check_number(v, f"{what} element {i} ({names[i]})") for i, v in enumerate(items)]
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = numbers_[:3]
    q = quaternion_from_rpy(*numbers_[3:]) if len(items) == 6 else normalized_quaternion(numbers_[3:], what)
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = q
    return pose


def pose_stamped_from_target(target: object, default_frame: str, what: str = "pose target") -> PoseStamped:
    """PoseStamped from any accepted pose-target form: 6/7-list, Pose or PoseStamped (empty frame: default)."""
    result = PoseStamped()
    if isinstance(target, PoseStamped):
        result.header = target.header
        result.pose = _checked_pose(target.pose, what)
    elif isinstance(target, Pose):
        result.pose = _checked_pose(target, what)
    else:
        result.pose = pose_from_list(target, what)
    if not result.header.frame_id:
        result.header.frame_id = default_frame
    return result


def _link_constraint(constraint: object, link: str, target: PoseStamped) -> object:
    """A position or orientation constraint's common fields: the target's header, the link, weight 1."""
    constraint.header = target.header
    constraint.link_name = link
    constraint.weight = 1.0
    return constraint


def position_constraint(link: str, target: PoseStamped, tolerance: float) -> PositionConstraint:
    """The link's origin within `tolerance` metres of the target position: the constraint region is a sphere of
    that radius centred there, as MoveIt's constructGoalConstraints builds it."""
    constraint = _link_constraint(PositionConstraint(), link, target)
    constraint.constraint_region.primitives.append(SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[tolerance]))
    centre = Pose()
    centre.position = target.pose.position
    centre.orientation.w = 1.0
    constraint.constraint_region.primitive_poses.append(centre)
    return constraint


def orientation_constraint(link: str, target: PoseStamped, tolerance: float) -> OrientationConstraint:
    """The link's orientation within `tolerance` radians about each axis of the target orientation."""
    constraint = _link_constraint(OrientationConstraint(), link, target)
    constraint.orientation = target.pose.orientation
    constraint.absolute_x_axis_tolerance = tolerance
    constraint.absolute_y_axis_tolerance = tolerance
    constraint.absolute_z_axis_tolerance = tolerance
    return constraint


def joint_constraints(values: Mapping[str, float], tolerance: float) -> Constraints:
    """One joint constraint per joint, tolerance above and below, weight 1."""
    constraints = Constraints()
    for name, value in values.items():
        constraint = JointConstraint()
        constraint.joint_name = name
        constraint.position = value
        constraint.tolerance_above = tolerance
        constraint.tolerance_below = tolerance
        constraint.weight = 1.0
        constraints.joint_constraints.append(constraint)
    return constraints


def _checked_setter(attribute: str, check: Callable[[object, str], float], doc: str) -> Callable[..., None]:
    """A method set_<attribute>(value) that sets the attribute to check(value, the attribute's name in words)."""

    def setter(self: object, value: float) -> None:
        setattr(self, attribute, check(value, attribute.replace("_", " ")))

    setter.__name__ = f"set_{attribute}"
    setter.__qualname__ = f"GoalBuilder.set_{attribute}"
    setter.__doc__ = doc
    return setter


class GoalBuilder:
    """The target and planning parameters of one group, as MoveGroupCommander keeps them.

    A pose target replaces a joint target and vice versa (the last one set is the active target).
    """

    JOINT, POSE, POSITION = "joint", "pose", "position"

    def __init__(self, group: Group, planning_frame: str) -> None:
        self.group = group
        self.planning_frame = planning_frame
        self.end_effector_link = group.end_effector_link
        self.planner_id = ""
        self.planning_time = 5.0
        self.num_planning_attempts = 1
        self.goal_joint_tolerance = 1e-4
        self.goal_position_tolerance = 1e-4
        self.goal_orientation_tolerance = 1e-3
        self.max_velocity_scaling_factor = 0.1
        self.max_acceleration_scaling_factor = 0.1
        self.start_state: RobotState | None = None
        self.path_constraints = Constraints()
        self.workspace = WorkspaceParameters()  # MoveGroupInterface's default: zero, no frame
        self.remembered: dict[str, dict[str, float]] = {}
        # The frame of pose targets and waypoints given without one (MoveIt's pose reference frame).
        self.pose_reference_frame = planning_frame
        self._kind: str | None = None
        self._joint_target: dict[str, float] = {}
        self._pose_target: PoseStamped | None = None
        self._alternative_pose_targets: list[PoseStamped] = []

    # Targets -----------------------------------------------------------------------------------------
    def set_pose_target(self, target: object) -> None:
        self._pose_target = pose_stamped_from_target(target, self.pose_reference_frame)
        self._alternative_pose_targets = []
        self._kind = self.POSE

    def set_pose_targets(self, targets: Sequence[object]) -> None:
        """Several pose targets of the end-effector link: reaching any one of them is success."""
        if isinstance(targets, str | Pose | PoseStamped) or not isinstance(targets, Sequence) or not targets:
            raise SixdofCommanderError("pose targets must be a non-empty list of poses")
        stamped = [
            pose_stamped_from_target(t, self.pose_reference_frame, f"pose target {i}") for i, t in enumerate(targets)
        ]
        self._pose_target, self._alternative_pose_targets = stamped[0], stamped[1:]
        self._kind = self.POSE

    def set_position_target(self, xyz: Sequence[float]) -> None:
        items = _check_sequence(xyz, "position target")
        if len(items) != 3:
            raise SixdofCommanderError(f"position target must have 3 elements (x, y, z), got {len(items)}")
        x, y, z = (check_number(v, f"position target element {i} ({'xyz'[i]})") for i, v in enumerate(items))
        # As in MoveIt: keep the orientation of an existing pose target (it is not constrained anyway).
        target = PoseStamped()
        if self._pose_target is not None:
            target.pose.orientation = self._pose_target.pose.orientation
        else:
            target.pose.orientation.w = 1.0
        target.header.frame_id = self.pose_reference_frame
        target.pose.position.x, target.pose.position.y, target.pose.position.z = x, y, z
        self._pose_target = target
        self._alternative_pose_targets = []
        self._kind = self.POSITION

    def set_joint_value_target(self, values: object, current: Mapping[str, float] | None = None) -> None:
        """values: a list in the group's joint order, or a dict name -> value (others from `current`)."""
        names = self.group.joint_names
        if isinstance(values, Mapping):
            mimics = self._mimic_joints()
            for name in values:
                if name in mimics:
                    raise SixdofCommanderError(
                        f"joint '{name}' mimics '{mimics[name]}' in group '{self.group.name}': set that one instead"
                    )
            unknown = sorted(str(k) for k in values if k not in names)
            if unknown:
                raise SixdofCommanderError(
                    f"joints {unknown} are not in group '{self.group.name}'; its joints: {names}"
                )
            missing = [n for n in names if n not in values]
            if missing and current is None:
                raise SixdofCommanderError(f"joint target for group '{self.group.name}' lacks joints {missing}")
            merged = {n: values[n] if n in values else current[n] for n in names}
        else:
            items = _check_sequence(values, "joint value target")
            if len(items) != len(names):
                raise SixdofCommanderError(
                    f"joint value target for group '{self.group.name}' must have {len(names)} values {names}, "
                    f"got {len(items)}"
                )
            merged = dict(zip(names, items, strict=True))
        checked = {}
        for joint in self.group.joints:
            value = check_number(merged[joint.name], f"joint target value of '{joint.name}'")
            # MoveIt accepts values within the goal tolerance of a bound.
            margin = self.goal_joint_tolerance
            # A continuous joint is unbounded: its -pi..pi is nominal (docs/design.md "One robot model").
            if joint.bounded and (value < joint.lower - margin or value > joint.upper + margin):
                raise SixdofCommanderError(
                    f"joint target {value:.6g} of '{joint.name}' is outside its limits [{joint.lower:.6g}, "
                    f"{joint.upper:.6g}]"
                )
            checked[joint.name] = value
        self._joint_target = checked
        self._kind = self.JOINT

    def named_targets(self) -> list[str]:
        return sorted(set(self.group.named_states) | set(self.remembered))

    def named_target_values(self, name: str) -> dict[str, float]:
        if name in self.remembered:
            return dict(self.remembered[name])
        if name in self.group.named_states:
            return dict(self.group.named_states[name])
        raise SixdofCommanderError(
            f"unknown named target '{name}' for group '{self.group.name}'; known: {self.named_targets()}"
        )

    def set_named_target(self, name: str, current: Mapping[str, float] | None = None) -> None:
        # SRDF states may list mimic joints too (MoveIt accepts them); their values follow the active joint.
        values = self.named_target_values(name)
        mimics = self._mimic_joints()
        self.set_joint_value_target({k: v for k, v in values.items() if k not in mimics}, current)

    def _mimic_joints(self) -> dict[str, str]:
        """Mimic joints of the group -> the joint each follows."""
        return {j.name: j.mimic for j in self.group.all_joints if j.mimic is not None}

    def remember_joint_values(self, name: str, values: Sequence[float]) -> None:
        items = _check_sequence(values, "remembered joint values")
        names = self.group.joint_names
        if len(items) != len(names):
            raise SixdofCommanderError(
                f"remembered joint values must have {len(names)} values {names}, got {len(items)}"
            )
        self.remembered[name] = {n: check_number(v, f"value of '{n}'") for n, v in zip(names, items, strict=True)}

    def forget_joint_values(self, name: str) -> None:
        if name not in self.remembered:
            raise SixdofCommanderError(
                f"no remembered joint values named '{name}'; remembered: {sorted(self.remembered)}"
            )
        del self.remembered[name]

    def clear_pose_targets(self) -> None:
        self._pose_target = None
        self._alternative_pose_targets = []
        if self._kind in (self.POSE, self.POSITION):
            self._kind = None

    @property
    def joint_target(self) -> dict[str, float]:
        return dict(self._joint_target)

    @property
    def pose_target(self) -> PoseStamped | None:
        return self._pose_target

    @property
    def has_target(self) -> bool:
        return self._kind is not None

    # Parameters --------------------------------------------------------------------------------------
    # set_<parameter>(value): the parameter becomes check(value), which raises naming the parameter.
    set_max_velocity_scaling_factor = _checked_setter(
        "max_velocity_scaling_factor", check_scaling_factor, "Scale the joints' maximum velocities by value in (0, 1]."
    )
    set_max_acceleration_scaling_factor = _checked_setter(
        "max_acceleration_scaling_factor",
        check_scaling_factor,
        "Scale the joints' maximum accelerations by value in (0, 1].",
    )
    set_goal_joint_tolerance = _checked_setter(
        "goal_joint_tolerance", check_positive, "Joint goal tolerance, radians or metres (default 1e-4)."
    )
    set_goal_position_tolerance = _checked_setter(
        "goal_position_tolerance", check_positive, "Position goal tolerance, metres (default 1e-4)."
    )
    set_goal_orientation_tolerance = _checked_setter(
        "goal_orientation_tolerance",
        check_positive,
        "Orientation goal tolerance about each axis, radians (default 1e-3).",
    )

    def set_planning_time(self, seconds: float) -> None:
        """Time allowed to plan, seconds (> 0; default 5)."""
        self.planning_time = check_positive(seconds, "planning time")

    def set_num_planning_attempts(self, num_planning_attempts: int) -> None:
        """Number of planning attempts (>= 1; the shortest solution wins)."""
        attempts = num_planning_attempts
        if isinstance(attempts, bool) or not isinstance(attempts, numbers.Integral) or attempts < 1:
            raise SixdofCommanderError(f"number of planning attempts must be an integer >= 1, got {attempts!r}")
        self.num_planning_attempts = int(attempts)

    def set_workspace(self, values: Sequence[float]) -> None:
        """The workspace box in the planning frame, as MoveIt's set_workspace: [] (all zero),
        [minX, minY, maxX, maxY] (z 0) or [minX, minY, minZ, maxX, maxY, maxZ] (checked numbers)."""
        corners = [0.0] * 6 if not values else list(values)
        if len(corners) == 4:
            corners = [corners[0], corners[1], 0.0, corners[2], corners[3], 0.0]
        workspace = WorkspaceParameters()
        workspace.header.frame_id = self.planning_frame
        low, high = workspace.min_corner, workspace.max_corner
        low.x, low.y, low.z, high.x, high.y, high.z = corners
        self.workspace = workspace

    def set_end_effector_link(self, link: str, known_links: frozenset[str]) -> None:
        if link not in known_links:
            raise SixdofCommanderError(f"end-effector link '{link}' is not a link of the robot")
        self.end_effector_link = link

    # Requests ----------------------------------------------------------------------------------------
    def goal_constraints(self) -> Constraints:
        """The active target as MoveIt's constructGoalConstraints builds it."""
        if self._kind is None:
            raise SixdofCommanderError(
                f"no target set for group '{self.group.name}': call set_pose_target, set_position_target, "
                "set_joint_value_target or set_named_target first"
            )
        if self._kind == self.JOINT:
            return joint_constraints(self._joint_target, self.goal_joint_tolerance)
        constraints = Constraints()
        link = self.end_effector_link
        constraints.position_constraints.append(
            position_constraint(link, self._pose_target, self.goal_position_tolerance)
        )
        if self._kind == self.POSE:
            constraints.orientation_constraints.append(
                orientation_constraint(link, self._pose_target, self.goal_orientation_tolerance)
            )
        return constraints

    def all_goal_constraints(self) -> list[Constraints]:
        """The active target's goal constraints, one per alternative pose target."""
        goals = [self.goal_constraints()]
        first = self._pose_target
        try:
            for alternative in self._alternative_pose_targets:
                self._pose_target = alternative
                goals.append(self.goal_constraints())
        finally:
            self._pose_target = first
        return goals

    def current_start_state(self) -> RobotState:
        """The start state: the one set, else 'the planner's current state' (an empty diff)."""
        if self.start_state is not None:
            return self.start_state
        state = RobotState()
        state.is_diff = True
        return state

    def motion_plan_request(self) -> MotionPlanRequest:
        """The request of the current targets and settings, built anew on each call. The fields are passed to the
        constructor, which then builds defaults only for the fields not given."""
        return MotionPlanRequest(
            workspace_parameters=self.workspace,
            start_state=self.current_start_state(),
            goal_constraints=self.all_goal_constraints(),
            path_constraints=self.path_constraints,
            planner_id=self.planner_id,
            group_name=self.group.name,
            num_planning_attempts=self.num_planning_attempts,
            allowed_planning_time=self.planning_time,
            max_velocity_scaling_factor=self.max_velocity_scaling_factor,
            max_acceleration_scaling_factor=self.max_acceleration_scaling_factor,
        )

    def move_group_goal(self) -> MoveGroupGoal:
        """The move_group action goal of go(): plan and execute, in the planner's current scene."""
        goal = MoveGroupGoal()
        goal.request = self.motion_plan_request()
        goal.planning_options.plan_only = False
        goal.planning_options.planning_scene_diff.is_diff = True
        goal.planning_options.planning_scene_diff.robot_state.is_diff = True
        return goal

    def cartesian_path_request(
        self,
        waypoints: Sequence[Pose],
        eef_step: float,
        jump_threshold: float,
        avoid_collisions: bool,
        path_constraints: Constraints | None = None,
    ) -> GetCartesianPathRequest:
        """The compute_cartesian_path request for the end-effector link through waypoints (the service times the
        path at full speed, as MoveIt's; the commander retimes it to its scaling factors)."""
        if isinstance(waypoints, Pose | PoseStamped) or not isinstance(waypoints, Sequence) or not waypoints:
            raise SixdofCommanderError("waypoints must be a non-empty list of geometry_msgs/Pose")
        request = GetCartesianPathRequest()
        request.header.frame_id = self.pose_reference_frame
        request.start_state = self.current_start_state()
        request.group_name = self.group.name
        request.link_name = self.end_effector_link
        for i, waypoint in enumerate(waypoints):
            if not isinstance(waypoint, Pose):
                raise SixdofCommanderError(f"waypoint {i} must be a geometry_msgs/Pose, got {type(waypoint).__name__}")
            stamped = pose_stamped_from_target(waypoint, self.pose_reference_frame, f"waypoint {i}")
            request.waypoints.append(stamped.pose)
        request.max_step = check_positive(eef_step, "eef_step")
        request.jump_threshold = check_number(jump_threshold, "jump_threshold")
        if request.jump_threshold < 0.0:
            raise SixdofCommanderError(f"jump_threshold must be >= 0 (0: no check), got {request.jump_threshold}")
        if not isinstance(avoid_collisions, bool):
            raise SixdofCommanderError(f"avoid_collisions must be True or False, got {avoid_collisions!r}")
        request.avoid_collisions = avoid_collisions
        if path_constraints is not None:
            request.path_constraints = path_constraints
        return request
