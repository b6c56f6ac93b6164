"""MoveGroup: MoveGroupCommander's API over the sixdof move_group node."""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import rospy
from geometry_msgs.msg import Pose, PoseStamped

from sixdof_msgs.msg import (
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    MoveGroupAction,
    MoveItErrorCodes,
    RobotState,
    RobotTrajectory,
)
from sixdof_msgs.srv import GetCartesianPath, GetMotionPlan, GetPositionFK

from ._ros import ActionClient, JointStateMonitor, ServerWaiter, load_robot_model, require_node, resolve
from .exceptions import SixdofCommanderError
from .goals import GoalBuilder
from .planning_scene import PlanningScene
from .robot_model import RobotDescription, SemanticDescription, resolve_group
from .transforms import rpy_from_quaternion

SERVICES = ("plan_kinematic_path", "compute_fk", "compute_cartesian_path", "get_planning_scene", "apply_planning_scene")


def error_code(value: int, message: str, source: str = "sixdof_commander") -> MoveItErrorCodes:
    """A MoveItErrorCodes message."""
    code = MoveItErrorCodes()
    code.val = value
    code.message = message
    code.source = source
    return code


class MoveGroup:
    """Plans and moves one planning group (MoveGroupCommander's method names and semantics).

    Targets and parameters are kept here; plan() calls the plan_kinematic_path service, go() the
    move_group action (plan and execute), execute() the execute_trajectory action.
    """

    def __init__(self, group_name: str, ns: str = "", wait_for_servers: float = 5.0) -> None:
        """Reads robot_description(_semantic) and waits up to wait_for_servers seconds (0: forever)
        for the move_group node's services and actions; SixdofCommanderError names what is missing."""
        require_node()
        self._ns = ns
        self._urdf, self._srdf = load_robot_model(ns)
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

        self._move_action = ActionClient(resolve(ns, "move_group"), MoveGroupAction)
        self._execute_action = ActionClient(resolve(ns, "execute_trajectory"), ExecuteTrajectoryAction)
        waiter = ServerWaiter(wait_for_servers)
        waiter.action(self._move_action, resolve(ns, "move_group"))
        waiter.action(self._execute_action, resolve(ns, "execute_trajectory"))
        for name in SERVICES:
            waiter.service(resolve(ns, name))
        waiter.check(f"MoveGroup('{group_name}')")

        self._plan_service = rospy.ServiceProxy(resolve(ns, "plan_kinematic_path"), GetMotionPlan)
        self._fk_service = rospy.ServiceProxy(resolve(ns, "compute_fk"), GetPositionFK)
        self._cartesian_service = rospy.ServiceProxy(resolve(ns, "compute_cartesian_path"), GetCartesianPath)
        self._joint_states = JointStateMonitor(resolve(ns, "joint_states"))
        self._scene = PlanningScene(ns, wait_for_servers=wait_for_servers)

    # Introspection -----------------------------------------------------------------------------------
    @property
    def robot_description(self) -> RobotDescription:
        """The parsed URDF."""
        return self._urdf

    @property
    def semantic_description(self) -> SemanticDescription:
        """The parsed SRDF."""
        return self._srdf

    def get_name(self) -> str:
        """The group's name."""
        return self._group.name

    def get_active_joints(self) -> list[str]:
        """The group's active joints, in order."""
        return self._group.joint_names

    def get_planning_frame(self) -> str:
        """The frame plans and poses are expressed in (the URDF root or the SRDF virtual joint's parent)."""
        return self._planning_frame

    def get_end_effector_link(self) -> str:
        """The link pose targets refer to (the SRDF end effector's parent link, else the group's tip)."""
        return self._goal.end_effector_link

    def set_end_effector_link(self, link_name: str) -> None:
        """Use another link for pose targets and current poses."""
        self._goal.set_end_effector_link(link_name, self._urdf.links)

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

    def set_position_target(self, xyz: Sequence[float], end_effector_link: str = "") -> None:
        """Target position of the end-effector link, orientation free."""
        self._use_link(end_effector_link)
        self._goal.set_position_target(xyz)

    def set_joint_value_target(self, values: Sequence[float] | Mapping[str, float]) -> None:
        """Joint target: a list in get_active_joints() order, or a dict (joints not named keep their
        current values). Values outside the URDF limits raise SixdofCommanderError."""
        current = None
        if isinstance(values, Mapping) and set(values) != set(self._group.joint_names):
            unknown = sorted(str(k) for k in values if k not in self._group.joint_names)
            current = None if unknown else self._joint_states.positions(self._group.joint_names)
        self._goal.set_joint_value_target(values, current)

    def set_named_target(self, name: str) -> None:
        """Joint target from an SRDF group state (or a remembered one) of this group."""
        self._goal.set_named_target(name)

    def get_named_targets(self) -> list[str]:
        """Names of the group's SRDF states and remembered joint values."""
        return self._goal.named_targets()

    def get_named_target_values(self, name: str) -> dict[str, float]:
        """Joint values of a named target, by joint name."""
        return self._goal.named_target_values(name)

    def remember_joint_values(self, name: str, values: Sequence[float] | None = None) -> None:
        """Store joint values (default: the current ones) as a named target."""
        if values is None:
            values = self.get_current_joint_values()
        self._goal.remember_joint_values(name, values)

    def get_joint_value_target(self) -> list[float]:
        """The joint target, in get_active_joints() order (empty without a joint target)."""
        target = self._goal.joint_target
        return [target[n] for n in self._group.joint_names] if target else []

    def get_pose_target(self) -> PoseStamped | None:
        """The pose target, or None."""
        return self._goal.pose_target

    def clear_pose_targets(self) -> None:
        """Forget the pose/position target."""
        self._goal.clear_pose_targets()

    def set_start_state(self, state: RobotState) -> None:
        """Plan from this state instead of the current one."""
        self._goal.start_state = state

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

    def set_num_planning_attempts(self, attempts: int) -> None:
        """Number of planning attempts (>= 1; the shortest solution wins)."""
        self._goal.set_num_planning_attempts(attempts)

    def set_planner_id(self, planner_id: str) -> None:
        """The planner to use, e.g. 'RRTConnect' ('' for the node's default)."""
        self._goal.planner_id = str(planner_id)

    def get_planner_id(self) -> str:
        """The planner requested ('' for the node's default)."""
        return self._goal.planner_id

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

    # Planning and execution --------------------------------------------------------------------------
    def plan(self) -> tuple[bool, RobotTrajectory, float, MoveItErrorCodes]:
        """Plan to the target: (success, trajectory, planning_time, error_code)."""
        request = self._goal.motion_plan_request()
        start = time.monotonic()
        try:
            response = self._plan_service(request).motion_plan_response
        except (rospy.ServiceException, rospy.ROSException) as err:
            self._last_error = error_code(MoveItErrorCodes.COMMUNICATION_FAILURE, f"plan_kinematic_path: {err}")
            return False, RobotTrajectory(), time.monotonic() - start, self._last_error
        self._last_error = response.error_code
        success = response.error_code.val == MoveItErrorCodes.SUCCESS
        return success, response.trajectory, response.planning_time, response.error_code

    def go(self, wait: bool = True) -> bool:
        """Plan to the target and execute (move_group action). Without wait, returns once sent."""
        return self._run_action(self._move_action, self._goal.move_group_goal(), "move_group", wait)

    def execute(self, trajectory: RobotTrajectory, wait: bool = True) -> bool:
        """Execute a planned trajectory (execute_trajectory action). Without wait, returns once sent."""
        if not isinstance(trajectory, RobotTrajectory):
            raise SixdofCommanderError(
                f"execute() needs a sixdof_msgs/RobotTrajectory, got {type(trajectory).__name__}"
            )
        if not trajectory.joint_trajectory.points:
            raise SixdofCommanderError("execute() got an empty trajectory (did planning fail?)")
        goal = ExecuteTrajectoryGoal()
        goal.trajectory = trajectory
        return self._run_action(self._execute_action, goal, "execute_trajectory", wait)

    def _run_action(self, client: ActionClient, goal: object, name: str, wait: bool) -> bool:
        client.send_goal(goal)
        if not wait:
            self._last_error = error_code(MoveItErrorCodes.SUCCESS, f"{name} goal sent")
            return True
        client.wait_for_result()
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

    # Current state -----------------------------------------------------------------------------------
    def get_current_joint_values(self) -> list[float]:
        """Current positions of the group's joints from joint_states, in get_active_joints() order."""
        positions = self._joint_states.positions(self._group.joint_names)
        return [positions[n] for n in self._group.joint_names]

    def get_current_state(self) -> RobotState:
        """The current joint positions of the whole robot, as a RobotState."""
        state = RobotState()
        state.joint_state = self._joint_states.joint_state()
        return state

    def get_current_pose(self, end_effector_link: str = "") -> PoseStamped:
        """Pose of the end-effector link (or the given link) in the planning frame (compute_fk service)."""
        link = end_effector_link or self._goal.end_effector_link
        if link not in self._urdf.links:
            raise SixdofCommanderError(f"link '{link}' is not a link of the robot")
        request = GetPositionFK._request_class()
        request.header.frame_id = self._planning_frame
        request.fk_link_names = [link]
        request.robot_state = self.get_current_state()
        try:
            response = self._fk_service(request)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"compute_fk call failed: {err}") from err
        if response.error_code.val != MoveItErrorCodes.SUCCESS or len(response.pose_stamped) != 1:
            raise SixdofCommanderError(
                f"compute_fk failed for link '{link}': {response.error_code.val} {response.error_code.message}"
            )
        return response.pose_stamped[0]

    def get_current_rpy(self, end_effector_link: str = "") -> list[float]:
        """[roll, pitch, yaw] (fixed axes, radians) of the end-effector link in the planning frame."""
        q = self.get_current_pose(end_effector_link).pose.orientation
        return list(rpy_from_quaternion((q.x, q.y, q.z, q.w)))

    # Cartesian paths ---------------------------------------------------------------------------------
    def compute_cartesian_path(
        self,
        waypoints: Sequence[Pose],
        eef_step: float,
        jump_threshold: float = 0.0,
        avoid_collisions: bool = True,
    ) -> tuple[RobotTrajectory, float]:
        """Straight-line path of the end-effector link through waypoints (Poses in the planning frame),
        interpolated every eef_step metres: (trajectory, fraction of the path achieved; -1 on error)."""
        request = self._goal.cartesian_path_request(waypoints, eef_step, jump_threshold, avoid_collisions)
        try:
            response = self._cartesian_service(request)
        except (rospy.ServiceException, rospy.ROSException) as err:
            self._last_error = error_code(MoveItErrorCodes.COMMUNICATION_FAILURE, f"compute_cartesian_path: {err}")
            return RobotTrajectory(), -1.0
        self._last_error = response.error_code
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            return response.solution, -1.0
        return response.solution, response.fraction

    # Attached objects --------------------------------------------------------------------------------
    def attach_object(self, object_name: str, link_name: str = "", touch_links: Sequence[str] | None = None) -> bool:
        """Attach a planning-scene object to link_name (default: the end-effector link)."""
        return self._scene.attach_object(object_name, link_name or self._goal.end_effector_link, touch_links)

    def detach_object(self, name: str = "") -> bool:
        """Detach an attached object (all of them with no name) back into the world."""
        return self._scene.detach_object(name)
