"""MoveGroup's path and trajectory constraints: joint and position path constraints go with every plan; what
move_group refuses (orientation and visibility path constraints, trajectory constraints) is refused here first."""

from __future__ import annotations

import copy

from moveit_msgs.msg import Constraints

from .exceptions import SixdofCommanderError
from .move_group_base import MoveGroupContext, has_constraints, refuse


def check_path_constraints(value: object, method: str, argument: str = "constraints") -> Constraints:
    """A copy of `value` if move_group can keep a path within it: a Constraints of joint and position constraints
    only (docs/design.md); SixdofCommanderError naming the method, its argument and what it holds otherwise."""
    if not isinstance(value, Constraints):
        what = type(value).__name__
        raise SixdofCommanderError(f"{method}: {argument} must be a moveit_msgs/Constraints, got {what}")
    for field, kind in (("orientation_constraints", "orientation"), ("visibility_constraints", "visibility")):
        if getattr(value, field):
            raise refuse(
                f"{method}({argument} with {field})",
                f"move_group keeps paths within joint and position constraints only, not {kind} constraints",
            )
    return copy.deepcopy(value)


class PathConstraints:
    """MoveGroupCommander's constraint methods (the path constraints are kept in MoveGroup's GoalBuilder)."""

    def __init__(self, context: MoveGroupContext) -> None:
        self._context = context

    def get_known_constraints(self) -> list[str]:
        """Names of stored constraints: none (MoveIt reads them from its warehouse database; there is none)."""
        return []

    def get_path_constraints(self) -> Constraints:
        """The path constraints every plan and go() keeps to (empty: none)."""
        return copy.deepcopy(self._context.goal.path_constraints)

    def set_path_constraints(self, value: Constraints | str | None) -> None:
        """Path constraints for the following plans: a Constraints with joint constraints (each joint within
        [position - tolerance_below, position + tolerance_above] along the path) and position constraints (a
        link's point inside a region); None or an empty Constraints clears them. A name (constraints stored in
        MoveIt's warehouse) and orientation or visibility constraints raise."""
        if value is None:
            self.clear_path_constraints()
        elif isinstance(value, str):
            raise refuse(f"set_path_constraints('{value}')", "there is no warehouse database of named constraints")
        else:
            self._context.goal.path_constraints = check_path_constraints(value, "set_path_constraints")

    def clear_path_constraints(self) -> None:
        """No path constraints."""
        self._context.goal.path_constraints = Constraints()

    def get_trajectory_constraints(self) -> Constraints:
        """The trajectory constraints: always empty."""
        return Constraints()

    def set_trajectory_constraints(self, value: Constraints | None) -> None:
        """None or an empty Constraints; anything else raises (move_group refuses trajectory constraints)."""
        if value is None or (isinstance(value, Constraints) and not has_constraints(value)):
            return
        raise refuse("set_trajectory_constraints", "move_group's planner does not support trajectory constraints")

    def clear_trajectory_constraints(self) -> None:
        """No trajectory constraints (the only setting move_group supports)."""

    def set_constraints_database(self, host: str, port: int) -> None:
        """Refused: there is no constraints warehouse."""
        raise refuse("set_constraints_database", "there is no warehouse database of constraints")
