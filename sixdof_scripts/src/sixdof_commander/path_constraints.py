"""MoveGroup's path and trajectory constraints: move_group plans without them, so only empty ones are accepted."""

from __future__ import annotations

from sixdof_msgs.msg import Constraints

from .move_group_base import MoveGroupBase, has_constraints, refuse


class PathConstraints(MoveGroupBase):
    """MoveGroupCommander's constraint methods: empty constraints are accepted, real ones raise."""

    def get_known_constraints(self) -> list[str]:
        """Names of stored constraints: none (MoveIt reads them from its warehouse database; there is none)."""
        return []

    def get_path_constraints(self) -> Constraints:
        """The path constraints: always empty (move_group plans without path constraints)."""
        return Constraints()

    def set_path_constraints(self, value: Constraints | str | None) -> None:
        """None or an empty Constraints clears them; any real path constraint raises (move_group's planner does
        not support path constraints: a plan would silently ignore them)."""
        if value is None or (isinstance(value, Constraints) and not has_constraints(value)):
            return
        raise refuse("set_path_constraints", "move_group's planner does not support path constraints")

    def clear_path_constraints(self) -> None:
        """No path constraints (the only setting move_group supports)."""

    def get_trajectory_constraints(self) -> Constraints:
        """The trajectory constraints: always empty."""
        return Constraints()

    def set_trajectory_constraints(self, value: Constraints | None) -> None:
        """None or an empty Constraints; anything else raises (not supported by move_group)."""
        if value is None or (isinstance(value, Constraints) and not has_constraints(value)):
            return
        raise refuse("set_trajectory_constraints", "move_group's planner does not support trajectory constraints")

    def clear_trajectory_constraints(self) -> None:
        """No trajectory constraints (the only setting move_group supports)."""

    def set_constraints_database(self, host: str, port: int) -> None:
        """Refused: there is no constraints warehouse."""
        raise refuse("set_constraints_database", "there is no warehouse database of constraints")
