"""MoveGroup's Cartesian paths: compute_cartesian_path under both MoveIt signatures (compute_cartesian_path service,
then retime_trajectory to the group's scaling factors)."""

from __future__ import annotations

import numbers
from collections.abc import Sequence

from geometry_msgs.msg import Pose
from moveit_msgs.msg import Constraints, RobotTrajectory

from .exceptions import SixdofCommanderError
from .move_group_base import MoveGroupContext
from .path_constraints import check_path_constraints


class CartesianPath:
    """MoveGroupCommander.compute_cartesian_path: the request from MoveGroup's GoalBuilder, sent by its clients."""

    def __init__(self, context: MoveGroupContext) -> None:
        self._context = context

    def compute_cartesian_path(
        self,
        waypoints: Sequence[Pose],
        eef_step: float,
        *args: object,
        path_constraints: Constraints | None = None,
        **kwargs: object,
    ) -> tuple[RobotTrajectory, float]:
        """Straight-line path of the end-effector link through waypoints (Poses in the pose reference frame),
        interpolated every eef_step metres: (trajectory, fraction of the path achieved; -1 on error). The path keeps
        to `path_constraints` (joint and position constraints; the group's own path constraints do not apply, as in
        MoveIt). move_group times it at full speed; it is retimed here to the group's scaling factors.

        Both MoveIt signatures: (waypoints, eef_step, avoid_collisions=True, path_constraints=None) (1.1.15 on) and
        (waypoints, eef_step, jump_threshold, avoid_collisions=True) (before): a number (not a bool) in third
        place is the jump threshold (0 = no jump check)."""
        jump_threshold, avoid_collisions = _cartesian_arguments(args, kwargs)
        constraints = None
        if path_constraints is not None:
            constraints = check_path_constraints(path_constraints, "compute_cartesian_path", "path_constraints")
        request = self._context.goal.cartesian_path_request(
            waypoints, eef_step, jump_threshold, avoid_collisions, constraints
        )
        return self._context.clients.cartesian_path(
            request, self._context.goal.max_velocity_scaling_factor, self._context.goal.max_acceleration_scaling_factor
        )


def _cartesian_arguments(args: tuple[object, ...], kwargs: dict[str, object]) -> tuple[float, bool]:
    """(jump_threshold, avoid_collisions) from compute_cartesian_path's positional/keyword arguments after eef_step."""
    unknown = sorted(set(kwargs) - {"jump_threshold", "avoid_collisions"})
    if unknown:
        raise SixdofCommanderError(f"compute_cartesian_path: unexpected keyword arguments {unknown}")
    jump_threshold: object = kwargs.get("jump_threshold", 0.0)
    avoid_collisions: object = kwargs.get("avoid_collisions", True)
    rest = list(args)
    if rest and not isinstance(rest[0], bool) and isinstance(rest[0], numbers.Real):
        if "jump_threshold" in kwargs:
            raise SixdofCommanderError("compute_cartesian_path: jump_threshold given twice")
        jump_threshold = rest.pop(0)
    if rest:
        if "avoid_collisions" in kwargs:
            raise SixdofCommanderError("compute_cartesian_path: avoid_collisions given twice")
        avoid_collisions = rest.pop(0)
    if rest:
        raise SixdofCommanderError(f"compute_cartesian_path: too many positional arguments ({len(args) + 2})")
    return jump_threshold, avoid_collisions
