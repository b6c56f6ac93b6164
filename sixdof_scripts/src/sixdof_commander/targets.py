"""MoveGroup's targets: the goal of the next plan (pose, position, joint values, IK-solved poses, named and
remembered states, random values) and the start state it is planned from."""

from __future__ import annotations

import copy
import numbers
from collections.abc import Mapping, Sequence

from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import MoveItErrorCodes, RobotState
from moveit_msgs.srv import GetPositionIK
from sensor_msgs.msg import JointState

from .current_state import CurrentState
from .exceptions import SixdofCommanderError
from .goals import check_number, pose_stamped_from_target
from .move_group_base import MoveGroupContext, refuse
from .transforms import rpy_from_quaternion


class Targets:
    """MoveGroupCommander's target setters and getters (kept in MoveGroup's GoalBuilder); pose targets solved by
    its clients' compute_ik, joints a target leaves out from its StateMonitor, the current pose and values from
    its CurrentState."""

    def __init__(self, context: MoveGroupContext, current: CurrentState) -> None:
        self._context = context
        self._current = current

    def _use_link(self, end_effector_link: str) -> None:
        if end_effector_link:
            self._context.goal.set_end_effector_link(end_effector_link, self._context.robot.links)

    def set_pose_target(self, pose: object, end_effector_link: str = "") -> None:
        """Target pose of the end-effector link: [x, y, z, roll, pitch, yaw] (radians, fixed axes),
        [x, y, z, qx, qy, qz, qw] (unit quaternion), a Pose or a PoseStamped (planning frame if no frame)."""
        self._use_link(end_effector_link)
        self._context.goal.set_pose_target(pose)

    def set_pose_targets(self, poses: Sequence[object], end_effector_link: str = "") -> None:
        """Several pose targets of the end-effector link: the plan reaches any one of them."""
        self._use_link(end_effector_link)
        self._context.goal.set_pose_targets(poses)

    def set_position_target(self, xyz: Sequence[float], end_effector_link: str = "") -> None:
        """Target position of the end-effector link, orientation free."""
        self._use_link(end_effector_link)
        self._context.goal.set_position_target(xyz)

    def set_rpy_target(self, rpy: Sequence[float], end_effector_link: str = "") -> None:
        """Refused: orientation-only goals (any position) are not supported by sixdof's move_group."""
        raise refuse("set_rpy_target", "move_group does not plan to orientation-only goals; use set_pose_target")

    def set_orientation_target(self, q: Sequence[float], end_effector_link: str = "") -> None:
        """Refused: orientation-only goals (any position) are not supported by sixdof's move_group."""
        raise refuse(
            "set_orientation_target", "move_group does not plan to orientation-only goals; use set_pose_target"
        )

    def shift_pose_target(self, axis: int, value: float, end_effector_link: str = "") -> None:
        """Pose target = the current pose with `value` added to one axis (0..5: x, y, z, roll, pitch, yaw)."""
        if isinstance(axis, bool) or not isinstance(axis, numbers.Integral) or not 0 <= axis <= 5:
            raise SixdofCommanderError(f"shift_pose_target: axis must be an integer 0..5 (x y z r p y), got {axis!r}")
        current = self._current.get_current_pose(end_effector_link)
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
            self._context.goal.set_joint_value_target(arg1)

    @staticmethod
    def _no_extra_arguments(*args: object) -> None:
        if any(a is not None for a in args):
            raise SixdofCommanderError("set_joint_value_target: too many arguments for this target form")

    def _set_joint_dict(self, values: Mapping[str, float]) -> None:
        current = None
        if set(values) != set(self._context.group.joint_names):
            unknown = sorted(str(k) for k in values if k not in self._context.group.joint_names)
            current = None if unknown else self._context.state.positions(self._context.group.joint_names)
        self._context.goal.set_joint_value_target(values, current)

    def _set_joint_state_target(self, msg: JointState, what: str) -> None:
        if len(msg.name) != len(msg.position):
            raise SixdofCommanderError(
                f"{what} has {len(msg.name)} names but {len(msg.position)} positions: they must match"
            )
        values = dict(zip(msg.name, msg.position, strict=True))
        # Joints of other groups in a whole-robot state are not part of this target (as MoveIt ignores them).
        group = self._context.group
        mine = {name: value for name, value in values.items() if name in group.joint_names}
        if not mine:
            raise SixdofCommanderError(f"{what} names none of the joints of group '{group.name}' {group.joint_names}")
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
        link = link or self._context.goal.end_effector_link
        if link not in self._context.robot.links:
            raise SixdofCommanderError(f"set_joint_value_target: link '{link}' is not a link of the robot")
        request = GetPositionIK._request_class()
        request.ik_request.group_name = self._context.group.name
        request.ik_request.robot_state.is_diff = True
        request.ik_request.ik_link_name = link
        request.ik_request.pose_stamped = pose_stamped_from_target(pose, self._context.goal.pose_reference_frame)
        response, outcome = self._context.clients.ik(request)
        if response is None:
            raise SixdofCommanderError(f"set_joint_value_target: compute_ik call failed: {outcome.message}")
        if outcome.val != MoveItErrorCodes.SUCCESS:
            # An exact solution is also the best approximate one; the solvers have no approximate mode beyond it.
            hint = " (approximate IK: the solvers return exact solutions only)" if approx else ""
            raise SixdofCommanderError(f"set_joint_value_target: no IK solution for link '{link}': {outcome}{hint}")
        solution = dict(zip(response.solution.joint_state.name, response.solution.joint_state.position, strict=False))
        return {name: solution[name] for name in self._context.group.joint_names if name in solution}

    def set_named_target(self, name: str) -> None:
        """Joint target from an SRDF group state (or a remembered one) of this group."""
        self._context.goal.set_named_target(name)

    def get_named_targets(self) -> list[str]:
        """Names of the group's SRDF states and remembered joint values."""
        return self._context.goal.named_targets()

    def get_named_target_values(self, target: str) -> dict[str, float]:
        """Joint values of a named target, by joint name."""
        return self._context.goal.named_target_values(target)

    def remember_joint_values(self, name: str, values: Sequence[float] | None = None) -> None:
        """Store joint values (default: the current ones) as a named target."""
        if values is None:
            values = self._current.get_current_joint_values()
        self._context.goal.remember_joint_values(name, values)

    def get_remembered_joint_values(self) -> dict[str, list[float]]:
        """Remembered joint values by name, each in get_active_joints() order."""
        return {
            name: [values[j] for j in self._context.group.joint_names]
            for name, values in self._context.goal.remembered.items()
        }

    def forget_joint_values(self, name: str) -> None:
        """Forget remembered joint values."""
        self._context.goal.forget_joint_values(name)

    def set_random_target(self) -> None:
        """A random joint target within the limits."""
        self.set_joint_value_target(self._current.get_random_joint_values())

    def get_joint_value_target(self) -> list[float]:
        """The joint target, in get_active_joints() order (empty without a joint target)."""
        target = self._context.goal.joint_target
        return [target[n] for n in self._context.group.joint_names] if target else []

    def get_pose_target(self) -> PoseStamped | None:
        """The pose target, or None."""
        return self._context.goal.pose_target

    def clear_pose_target(self, end_effector_link: str) -> None:
        """Forget the pose target of that end-effector link (this group has one pose target at a time)."""
        if end_effector_link in ("", self._context.goal.end_effector_link):
            self._context.goal.clear_pose_targets()

    def clear_pose_targets(self) -> None:
        """Forget the pose/position target."""
        self._context.goal.clear_pose_targets()

    def set_start_state(self, msg: RobotState) -> None:
        """Plan from this state instead of the current one: a copy of `msg`, as MoveIt's commander takes it, so that
        changing the message afterwards does not change the next plan's start."""
        if not isinstance(msg, RobotState):
            raise SixdofCommanderError(f"set_start_state needs a RobotState, got {type(msg).__name__}")
        if len(msg.joint_state.name) != len(msg.joint_state.position):
            raise SixdofCommanderError(
                f"start state has {len(msg.joint_state.name)} joint names but {len(msg.joint_state.position)} "
                "positions: they must match"
            )
        self._context.goal.start_state = copy.deepcopy(msg)

    def set_start_state_to_current_state(self) -> None:
        """Plan from the planner's current state (the default)."""
        self._context.goal.start_state = None
