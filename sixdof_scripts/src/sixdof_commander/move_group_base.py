"""What MoveGroup's parts share: the attributes MoveGroup.__init__ sets, error codes, and the refusal of the
MoveGroupCommander methods sixdof does not offer."""

from __future__ import annotations

import numpy as np
from moveit_msgs.msg import Constraints

from .exceptions import MoveItCommanderException, SixdofCommanderError
from .goals import GoalBuilder
from .move_group_clients import MoveGroupClients
from .planning_scene import PlanningScene
from .robot_model import Group, RobotDescription, SemanticDescription
from .state_monitor import StateMonitor


class MoveGroupBase:
    """The state of one MoveGroup. MoveGroup.__init__ sets it; MoveGroup's parts (targets.py, planning_options.py,
    path_constraints.py, current_state.py, cartesian_path.py, retiming.py), each a mixin, use it."""

    _ns: str
    _urdf: RobotDescription
    _srdf: SemanticDescription
    _group: Group
    _planning_frame: str
    _goal: GoalBuilder  # targets and planning parameters, and the requests built from them
    _support_surface: str
    _clients: MoveGroupClients  # move_group's actions and services, the last call's outcome
    _state: StateMonitor  # the current joint values (joint_states)
    _scene: PlanningScene
    _rng: np.random.Generator


def refuse(method: str, why: str) -> MoveItCommanderException:
    """The error a MoveGroupCommander method sixdof does not offer raises."""
    call = method if "(" in method else f"{method}()"
    return SixdofCommanderError(f"{call} is not available on sixdof: {why}")


def has_constraints(value: Constraints) -> bool:
    """True when the Constraints message holds any constraint."""
    return bool(
        value.joint_constraints
        or value.position_constraints
        or value.orientation_constraints
        or value.visibility_constraints
    )
