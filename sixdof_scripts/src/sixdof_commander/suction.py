"""SuctionGripper: the vacuum of a suction tool, and where its TCP goes to pick an object.

The vacuum is a control_msgs/GripperCommand action (the simulator serves it on `<controller>/gripper_cmd`:
`command.position > 0` turns it on, `<= 0` off, `result.stalled` is true while the cup holds an object). A pick
script's words mean what it expects: grasp() turns the vacuum on, release() turns it off; open() is release() and
close() is grasp(), so code written for a fingered Gripper picks with a cup too (a raw GripperCommand with a
positive position, a fingered gripper's "open", turns the vacuum ON).
"""

from __future__ import annotations

import numpy as np
from control_msgs.msg import GripperCommandAction, GripperCommandResult

from ._ros import ActionClient, ServerWaiter, check_timeout, require_node, resolve
from .grasping import ObjectGeometry, preferred_yaw, top_down_rotation
from .gripper import send_gripper_command
from .transforms import homogeneous

VACUUM_ON = 1.0
VACUUM_OFF = 0.0


class SuctionGripper:
    """The vacuum of a suction tool (a config package's grasping.yaml `suction`, served by move_group's
    get_robot_model: its `vacuum_controller`)."""

    is_suction = True

    def __init__(
        self,
        ns: str = "",
        action_name: str = "gripper_controller/gripper_cmd",
        wait_for_servers: float = 5.0,
        result_timeout: float = 60.0,
    ) -> None:
        """result_timeout: wall-clock seconds a command waits for its result (0: no limit); then, or as soon as the
        action server is lost, the goal is canceled and SixdofCommanderError raised."""
        require_node()
        self._result_timeout = check_timeout(result_timeout, "result_timeout")
        self._client = ActionClient(resolve(ns, action_name), GripperCommandAction)
        waiter = ServerWaiter(wait_for_servers)
        waiter.action(self._client, resolve(ns, action_name))
        waiter.check("SuctionGripper")
        self.last_status_text = ""
        # Whether the vacuum is on as this client last commanded it (None: unknown, no command reached its goal yet).
        self.vacuum: bool | None = None

    def grasp(self) -> GripperCommandResult:
        """Vacuum on; the result's `stalled` says whether the cup holds an object."""
        return self._command(VACUUM_ON)

    def release(self) -> GripperCommandResult:
        """Vacuum off: a held object is let go."""
        return self._command(VACUUM_OFF)

    def close(self, max_effort: float = 0.0) -> GripperCommandResult:
        """grasp() (vacuum on), under a fingered gripper's name; max_effort is not used."""
        return self.grasp()

    def open(self, max_effort: float = 0.0) -> GripperCommandResult:
        """release() (vacuum off), under a fingered gripper's name; max_effort is not used."""
        return self.release()

    def _command(self, position: float) -> GripperCommandResult:
        self.vacuum = None
        result, self.last_status_text = send_gripper_command(self._client, position, 0.0, self._result_timeout)
        self.vacuum = position > 0.0 if result.reached_goal else None
        return result


def suction_tcp_pose(geometry: ObjectGeometry) -> np.ndarray:
    """The TCP (the cup's face, z along the approach) on the centre of the object's top, tool z down, with the wrist
    yaw preferred at the object's position (a cup seals whichever way it is turned)."""
    centre = geometry.pose[:3, 3]
    yaw = preferred_yaw(centre[0], centre[1])
    return homogeneous([centre[0], centre[1], centre[2] + geometry.height / 2.0], top_down_rotation(yaw))
