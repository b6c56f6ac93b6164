"""MoveGroup's connections to the move_group node: its actions (move_group, execute_trajectory) and query services
(plan_kinematic_path, compute_fk, compute_ik, compute_cartesian_path, retime_trajectory), each call's outcome in
words (ErrorReports), and the outcome of the last plan/go/execute/compute_cartesian_path call."""

from __future__ import annotations

import threading

import rospy
from moveit_msgs import srv as moveit_srv
from moveit_msgs.msg import (
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    MotionPlanRequest,
    MoveGroupAction,
    MoveGroupGoal,
    MoveItErrorCodes,
    RobotTrajectory,
)

from sixdof_msgs.srv import RetimeTrajectory, RetimeTrajectoryRequest

from ._ros import ActionClient, ServerWaiter, resolve, wait_for_done
from ._service import SERVICE_TIMEOUT, PersistentService, call_service
from .error_reports import SUCCESS, CallError, ErrorReports

# move_group's moveit_msgs services and actions under MoveIt's names: {name: service type} and
# {name: (action type, goal type)}.
MOVE_GROUP_SERVICES = {
    "plan_kinematic_path": moveit_srv.GetMotionPlan,
    "compute_cartesian_path": moveit_srv.GetCartesianPath,
    "compute_fk": moveit_srv.GetPositionFK,
    "compute_ik": moveit_srv.GetPositionIK,
    "check_state_validity": moveit_srv.GetStateValidity,
    "get_planning_scene": moveit_srv.GetPlanningScene,
    "apply_planning_scene": moveit_srv.ApplyPlanningScene,
}
MOVE_GROUP_ACTIONS = {
    "move_group": (MoveGroupAction, MoveGroupGoal),
    "execute_trajectory": (ExecuteTrajectoryAction, ExecuteTrajectoryGoal),
}
# The services a MoveGroup waits for.
SERVICES = (
    "plan_kinematic_path",
    "compute_fk",
    "compute_cartesian_path",
    "get_planning_scene",
    "apply_planning_scene",
    "get_robot_model",
    "retime_trajectory",
)


class MoveGroupClients:
    """The move_group node's actions and services as one MoveGroup uses them. The services keep their connection
    between calls (PersistentService).

    plan(), move(), execute() and cartesian_path() record their outcome in `last_error`; the queries fk() and ik()
    return theirs.
    """

    def __init__(self, ns: str, wait_for_servers: float, who: str) -> None:
        """Waits up to wait_for_servers seconds (0: forever) for the actions and services; SixdofCommanderError
        naming `who` and what is missing otherwise."""
        waiter = ServerWaiter(wait_for_servers)
        actions = {name: ActionClient(resolve(ns, name), types[0]) for name, types in MOVE_GROUP_ACTIONS.items()}
        for name, client in actions.items():
            waiter.action(client, resolve(ns, name))
        self._move_action, self._execute_action = actions["move_group"], actions["execute_trajectory"]
        for name in SERVICES:
            waiter.service(resolve(ns, name))
        waiter.check(who)
        self._reports = ErrorReports(ns)
        self._plan_service, self._fk_service, self._ik_service, self._cartesian_service = (
            PersistentService(resolve(ns, name), MOVE_GROUP_SERVICES[name])
            for name in ("plan_kinematic_path", "compute_fk", "compute_ik", "compute_cartesian_path")
        )
        self._retime_service = PersistentService(resolve(ns, "retime_trajectory"), RetimeTrajectory)
        self.last_error: CallError = SUCCESS

    # Queries (their outcome is returned, last_error is kept) ---------------------------------------------
    def fk(self, request: object) -> tuple[object | None, CallError]:
        """compute_fk: (response or None, outcome)."""
        return self._reports.call(self._fk_service, request)

    def ik(self, request: object) -> tuple[object | None, CallError]:
        """compute_ik: (response or None, outcome)."""
        return self._reports.call(self._ik_service, request)

    def retime(
        self, trajectory: RobotTrajectory, velocity: float, acceleration: float
    ) -> tuple[RobotTrajectory | None, CallError]:
        """The trajectory's path timed by move_group's retime_trajectory (its time-optimal parameterization, the one
        every plan gets) at these scaling factors: (trajectory, SUCCESS), or (None, the failure in words)."""
        service = self._retime_service
        request = RetimeTrajectoryRequest(
            trajectory=trajectory, velocity_scaling_factor=velocity, acceleration_scaling_factor=acceleration
        )
        try:
            response = call_service(service, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            return None, CallError(MoveItErrorCodes.COMMUNICATION_FAILURE, f"{service.resolved_name}: {err}")
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            return None, CallError(response.error_code.val, response.error_message, service.resolved_name)
        return response.trajectory, SUCCESS

    # Calls whose outcome is last_error -------------------------------------------------------------------
    def plan(self, request: MotionPlanRequest) -> object | None:
        """plan_kinematic_path: its response, None when it gave no answer (in time: the request's planning time
        over all attempts, plus SERVICE_TIMEOUT)."""
        timeout = request.allowed_planning_time * max(request.num_planning_attempts, 1) + SERVICE_TIMEOUT
        answer, self.last_error = self._reports.call(
            self._plan_service, request, timeout, lambda r: r.motion_plan_response.error_code.val
        )
        if self.last_error.val != MoveItErrorCodes.SUCCESS:
            rospy.logwarn(f"plan: {self.last_error}")
        return answer

    def cartesian_path(self, request: object, velocity: float, acceleration: float) -> tuple[RobotTrajectory, float]:
        """compute_cartesian_path, its solution retimed to these scaling factors: (trajectory, fraction achieved;
        -1 on error)."""
        response, self.last_error = self._reports.call(self._cartesian_service, request)
        if response is None or self.last_error.val != MoveItErrorCodes.SUCCESS:
            return (RobotTrajectory() if response is None else response.solution), -1.0
        solution = response.solution
        if len(solution.joint_trajectory.points) >= 2:
            solution, self.last_error = self.retime(solution, velocity, acceleration)
            if solution is None:
                return RobotTrajectory(), -1.0
        return solution, response.fraction

    def move(self, goal: MoveGroupGoal, wait: bool) -> bool:
        """The move_group action (plan and execute); without wait, True once the goal is sent."""
        return self._run_action(self._move_action, goal, "move_group", wait)

    def execute(self, trajectory: RobotTrajectory, wait: bool) -> bool:
        """The execute_trajectory action; without wait, True once the goal is sent."""
        goal = ExecuteTrajectoryGoal()
        goal.trajectory = trajectory
        return self._run_action(self._execute_action, goal, "execute_trajectory", wait)

    def stop(self) -> None:
        """Cancels every goal of both actions."""
        self._move_action.cancel_all_goals()
        self._execute_action.cancel_all_goals()

    def _run_action(self, client: ActionClient, goal: object, name: str, wait: bool) -> bool:
        done = threading.Event()
        client.send_goal(goal, done_cb=lambda _state, _result: done.set())
        if not wait:
            self.last_error = CallError(MoveItErrorCodes.SUCCESS, f"{name} goal sent")
            return True
        reason = wait_for_done(client, done)
        if reason:
            client.stop_tracking_goal()
            self.last_error = CallError(MoveItErrorCodes.COMMUNICATION_FAILURE, f"{name}: {reason}")
            rospy.logerr(str(self.last_error))
            return False
        result = client.get_result()
        if result is None:
            self.last_error = CallError(
                MoveItErrorCodes.COMMUNICATION_FAILURE, f"{name}: no result (goal status {client.get_state()})"
            )
            return False
        # The words of a failure are the goal's status text (actionlib's set_aborted(result, text)).
        success = result.error_code.val == MoveItErrorCodes.SUCCESS
        self.last_error = CallError(result.error_code.val, "" if success else client.get_goal_status_text(), name)
        if not success:
            rospy.logwarn(f"{name}: {self.last_error}")
        return success
