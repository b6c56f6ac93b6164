"""MoveGroup's view of the robot's current state: joint values, RobotState, link poses (compute_fk), random values
and poses, the Jacobian and joint bounds."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from geometry_msgs.msg import PoseStamped
from moveit_msgs.msg import MoveItErrorCodes, RobotState
from moveit_msgs.srv import GetPositionFK

from .exceptions import SixdofCommanderError
from .goals import check_number
from .kinematics import bounded
from .move_group_base import MoveGroupContext
from .transforms import rpy_from_quaternion


class CurrentState:
    """MoveGroupCommander's current-state queries: MoveGroup's StateMonitor (joint_states) and its clients'
    compute_fk; poses are of the GoalBuilder's end-effector link unless another is given."""

    def __init__(self, context: MoveGroupContext) -> None:
        self._context = context

    def get_current_joint_values(self) -> list[float]:
        """Current positions of the group's joints from joint_states, in get_active_joints() order."""
        positions = self._context.state.positions(self._context.group.joint_names)
        return [positions[n] for n in self._context.group.joint_names]

    def get_current_state(self) -> RobotState:
        """The current joint positions of the whole robot, as a RobotState (mimic joints computed from their
        sources, as MoveIt's RobotState does)."""
        return self._context.state.current_state()

    def get_current_state_bounded(self) -> RobotState:
        """The current state with every joint value moved into its limits."""
        return self.enforce_bounds(self.get_current_state())

    def _fk(self, link: str, state: RobotState) -> PoseStamped:
        if link not in self._context.robot.links:
            raise SixdofCommanderError(f"link '{link}' is not a link of the robot")
        request = GetPositionFK._request_class()
        request.header.frame_id = self._context.planning_frame
        request.fk_link_names = [link]
        request.robot_state = state
        response, outcome = self._context.clients.fk(request)
        if response is None:
            raise SixdofCommanderError(f"compute_fk call failed: {outcome.message}")
        if outcome.val != MoveItErrorCodes.SUCCESS or len(response.pose_stamped) != 1:
            raise SixdofCommanderError(f"compute_fk failed for link '{link}': {outcome}")
        return response.pose_stamped[0]

    def get_current_pose(self, end_effector_link: str = "") -> PoseStamped:
        """Pose of the end-effector link (or the given link) in the planning frame (compute_fk service)."""
        return self._fk(end_effector_link or self._context.goal.end_effector_link, self.get_current_state())

    def get_current_rpy(self, end_effector_link: str = "") -> list[float]:
        """[roll, pitch, yaw] (fixed axes, radians) of the end-effector link in the planning frame."""
        q = self.get_current_pose(end_effector_link).pose.orientation
        return list(rpy_from_quaternion((q.x, q.y, q.z, q.w)))

    def get_random_joint_values(self) -> list[float]:
        """Uniformly random joint values within the limits, in get_active_joints() order (the core's sampler)."""
        return self._context.kinematics().random_group_values(self._context.group.name)

    def get_random_pose(self, end_effector_link: str = "") -> PoseStamped:
        """Pose of the end-effector link at random joint values (compute_fk), in the planning frame."""
        state = RobotState()
        state.is_diff = True
        state.joint_state.name = self._context.group.joint_names
        state.joint_state.position = self.get_random_joint_values()
        return self._fk(end_effector_link or self._context.goal.end_effector_link, state)

    def get_jacobian_matrix(
        self, joint_values: Sequence[float], reference_point: Sequence[float] | None = None
    ) -> np.ndarray:
        """Jacobian (numpy 6 x n: linear rows then angular, planning frame) of the group's tip link (at
        reference_point in its frame, default its origin) at joint_values (get_active_joints() order)."""
        names = self._context.group.joint_names
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
        group = self._context.group
        return self._context.kinematics().jacobian(group.name, group.tip_link, values, point)

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
        joints = self._context.robot.joints
        result.joint_state.position = [
            bounded(joints[n], p) if n in joints else p for n, p in zip(source.name, source.position, strict=True)
        ]
        return result
