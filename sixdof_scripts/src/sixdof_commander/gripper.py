"""Gripper: open/close/set_position through a control_msgs/GripperCommand action (the simulator's
gripper_controller/gripper_cmd)."""

from __future__ import annotations

import threading

from control_msgs.msg import GripperCommandAction, GripperCommandGoal, GripperCommandResult

from ._ros import ActionClient, ServerWaiter, check_timeout, load_robot_model, require_node, resolve, wait_for_done
from .exceptions import SixdofCommanderError
from .goals import check_number
from .robot_model import resolve_group


class Gripper:
    """A gripper with one actuated joint (the others mimic it): positions are that joint's (metres for prismatic
    fingers, radians for revolute ones); open()/close() go to the SRDF states `open_state` and `close_state` of the
    group, whichever way closing moves the joint."""

    def __init__(
        self,
        ns: str = "",
        group_name: str = "gripper",
        action_name: str = "gripper_controller/gripper_cmd",
        wait_for_servers: float = 5.0,
        result_timeout: float = 60.0,
        open_state: str = "open",
        close_state: str = "close",
    ) -> None:
        """result_timeout: wall-clock seconds a command waits for its result (0: no limit); then, or as soon as
        the action server is lost (its node died), the goal is canceled and SixdofCommanderError raised."""
        require_node()
        self._result_timeout = check_timeout(result_timeout, "result_timeout")
        self._client = ActionClient(resolve(ns, action_name), GripperCommandAction)
        waiter = ServerWaiter(wait_for_servers)
        waiter.action(self._client, resolve(ns, action_name))
        # The model (the group's joint, limits and named states) comes from move_group.
        waiter.service(resolve(ns, "get_robot_model"))
        if waiter.missing and not any("get_robot_model" in m for m in waiter.missing):
            # move_group answers: a robot without that group has no gripper, which says more than the missing action.
            _, srdf = load_robot_model(ns, timeout=wait_for_servers)
            if group_name not in srdf.groups:
                raise SixdofCommanderError(
                    f"Gripper: the robot has no gripper: its SRDF has no group '{group_name}' (groups: "
                    f"{sorted(srdf.groups)}) and {', '.join(waiter.missing)} is not served"
                )
        waiter.check("Gripper")
        urdf, srdf = load_robot_model(ns, timeout=wait_for_servers)
        group = resolve_group(urdf, srdf, group_name)
        if len(group.joints) != 1:
            raise SixdofCommanderError(
                f"gripper group '{group_name}' must have one actuated joint (others mimic it), has {group.joint_names}"
            )
        self._joint = group.joints[0]
        self._group = group
        self.last_status_text = ""
        self._positions = {}
        for key, state in (("open", open_state), ("close", close_state)):
            if state not in group.named_states or self._joint.name not in group.named_states[state]:
                raise SixdofCommanderError(
                    f"the SRDF has no state '{state}' of group '{group_name}' with joint '{self._joint.name}'"
                )
            self._positions[key] = group.named_states[state][self._joint.name]

    @property
    def joint_name(self) -> str:
        """The actuated finger joint."""
        return self._joint.name

    @property
    def velocity(self) -> float:
        """The finger joint's URDF velocity limit (inf when the URDF gives none): the speed the fingers move at."""
        return self._joint.velocity

    @property
    def open_position(self) -> float:
        """The finger joint's position in the open state."""
        return self._positions["open"]

    @property
    def close_position(self) -> float:
        """The finger joint's position in the closed state."""
        return self._positions["close"]

    def grasp(self, max_effort: float = 0.0) -> GripperCommandResult:
        """close(): what a pick script calls to take hold (a SuctionGripper's vacuum on)."""
        return self.close(max_effort)

    def release(self, max_effort: float = 0.0) -> GripperCommandResult:
        """open(): what a pick script calls to let go (a SuctionGripper's vacuum off)."""
        return self.open(max_effort)

    def open(self, max_effort: float = 0.0) -> GripperCommandResult:
        """Move the fingers to the open state; the action result."""
        return self.set_position(self.open_position, max_effort)

    def close(self, max_effort: float = 0.0) -> GripperCommandResult:
        """Close the fingers towards the closed state (they stall on a grasped object); the action result."""
        return self.set_position(self.close_position, max_effort)

    def set_position(self, position: float, max_effort: float = 0.0) -> GripperCommandResult:
        """Move the fingers to `position` (within the joint's URDF limits) with at most max_effort newtons
        (0: the joint's effort limit); waits for and returns the result (position, effort, stalled,
        reached_goal)."""
        value = check_number(position, "gripper position")
        if not self._joint.lower <= value <= self._joint.upper:
            raise SixdofCommanderError(
                f"gripper position {value:.6g} is outside the limits [{self._joint.lower:.6g}, "
                f"{self._joint.upper:.6g}] of '{self._joint.name}'"
            )
        effort = check_number(max_effort, "gripper max_effort")
        if effort < 0.0:
            raise SixdofCommanderError(f"gripper max_effort must be >= 0 (0: the joint's limit), got {effort}")
        result, self.last_status_text = send_gripper_command(self._client, value, effort, self._result_timeout)
        return result


def send_gripper_command(
    client: ActionClient, position: float, max_effort: float, result_timeout: float
) -> tuple[GripperCommandResult, str]:
    """Sends a GripperCommand goal and waits (wall clock: with use_sim_time a paused or stopped simulator never
    advances ROS time) for (its result, the goal status text: the controller's words when it aborted or rejected
    it). A timeout or a lost server cancels the goal and raises SixdofCommanderError."""
    goal = GripperCommandGoal()
    goal.command.position = position
    goal.command.max_effort = max_effort
    done = threading.Event()
    client.send_goal(goal, done_cb=lambda _state, _result: done.set())
    reason = wait_for_done(client, done, result_timeout)
    if reason:
        client.cancel_goal()
        raise SixdofCommanderError(
            f"gripper command to {position:.6g}: {reason} (goal state {client.get_state()}); the goal was canceled"
        )
    result = client.get_result()
    if result is None:
        raise SixdofCommanderError(f"gripper command got no result (goal status {client.get_state()})")
    return result, client.get_goal_status_text()
