"""MoveGroup's planning options: velocity/acceleration scaling, planning time and attempts, planner and pipeline,
goal tolerances, workspace, support surface, and the MoveIt options sixdof refuses (looking, replanning)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .exceptions import SixdofCommanderError
from .goals import check_number
from .move_group_base import MoveGroupContext, refuse

# The GoalBuilder setters that are MoveGroup's methods as they are.
GOAL_SETTERS = (
    "set_max_velocity_scaling_factor",
    "set_max_acceleration_scaling_factor",
    "set_planning_time",
    "set_num_planning_attempts",
    "set_goal_joint_tolerance",
    "set_goal_position_tolerance",
    "set_goal_orientation_tolerance",
)


class PlanningOptions:
    """MoveGroupCommander's planning parameters (kept in MoveGroup's GoalBuilder, whose setters MoveGroup serves
    itself: GOAL_SETTERS) and the support surface name."""

    def __init__(self, context: MoveGroupContext) -> None:
        self._context = context
        self._support_surface = ""

    def get_max_velocity_scaling_factor(self) -> float:
        """The velocity scaling factor plans and Cartesian paths are timed with (sixdof extension, for symmetry)."""
        return self._context.goal.max_velocity_scaling_factor

    def get_max_acceleration_scaling_factor(self) -> float:
        """The acceleration scaling factor plans and Cartesian paths are timed with (sixdof extension, for symmetry)."""
        return self._context.goal.max_acceleration_scaling_factor

    def get_planning_time(self) -> float:
        """Time allowed to plan, seconds."""
        return self._context.goal.planning_time

    def set_planner_id(self, planner_id: str) -> None:
        """The planner to use, e.g. 'RRTConnect' ('' for the node's default)."""
        self._context.goal.planner_id = str(planner_id)

    def get_planner_id(self) -> str:
        """The planner requested ('' for the node's default)."""
        return self._context.goal.planner_id

    def set_planning_pipeline_id(self, planning_pipeline: str) -> None:
        """The planning pipeline: move_group has one, 'ompl' ('' means it too); others raise."""
        if planning_pipeline not in ("", "ompl"):
            raise SixdofCommanderError(
                f"planning pipeline '{planning_pipeline}' is not available: sixdof's move_group has one, 'ompl'"
            )

    def get_planning_pipeline_id(self) -> str:
        """The planning pipeline ('ompl', the only one)."""
        return "ompl"

    def set_goal_tolerance(self, value: float) -> None:
        """Set the joint, position and orientation goal tolerances at once."""
        goal = self._context.goal
        goal.set_goal_joint_tolerance(value)
        goal.set_goal_position_tolerance(value)
        goal.set_goal_orientation_tolerance(value)

    def get_goal_tolerance(self) -> tuple[float, float, float]:
        """(joint, position, orientation) goal tolerances."""
        g = self._context.goal
        return (g.goal_joint_tolerance, g.goal_position_tolerance, g.goal_orientation_tolerance)

    def get_goal_joint_tolerance(self) -> float:
        """Joint goal tolerance."""
        return self._context.goal.goal_joint_tolerance

    def get_goal_position_tolerance(self) -> float:
        """Position goal tolerance (radius of a sphere around the target, metres)."""
        return self._context.goal.goal_position_tolerance

    def get_goal_orientation_tolerance(self) -> float:
        """Orientation goal tolerance (about each axis, radians)."""
        return self._context.goal.goal_orientation_tolerance

    def allow_looking(self, value: bool) -> None:
        """Looking around (moving sensors to clear unknown space) is not supported: only False is accepted."""
        if value:
            raise refuse("allow_looking(True)", "move_group has no sensor to look around with")

    def allow_replanning(self, value: bool) -> None:
        """Replanning after an environment change during execution is not supported: only False is accepted."""
        if value:
            raise refuse(
                "allow_replanning(True)",
                "move_group does not replan during execution; a failed go() returns False and can be retried",
            )

    def set_workspace(self, ws: Sequence[float]) -> None:
        """[] (none), [minX, minY, maxX, maxY] (z 0) or [minX, minY, minZ, maxX, maxY, maxZ], in the planning frame,
        sent as every request's workspace_parameters. As in MoveIt it bounds only the position of a floating or
        planar base joint; a robot with a fixed base has none, so it does not restrict an arm. Robots with such
        joints raise (sixdof does not plan for them)."""
        if isinstance(ws, str) or not isinstance(ws, Sequence | np.ndarray) or len(ws) not in (0, 4, 6):
            raise SixdofCommanderError(
                f"set_workspace needs [], [minX, minY, maxX, maxY] or [minX, minY, minZ, maxX, maxY, maxZ], got {ws!r}"
            )
        values = [check_number(v, f"workspace element {i}") for i, v in enumerate(ws)]
        half = len(values) // 2
        if any(values[i] > values[i + half] for i in range(half)):
            raise SixdofCommanderError(f"set_workspace: a minimum exceeds its maximum in {values}")
        mobile = [j.name for j in self._context.robot.joints.values() if j.type in ("floating", "planar")]
        if values and mobile:
            raise refuse("set_workspace", f"the robot's base joints {mobile} are not planned by sixdof")
        self._context.goal.set_workspace(values)

    def set_support_surface_name(self, value: str) -> None:
        """The support surface of pick/place (MoveIt uses it only there). Stored and reported by
        get_support_surface_name(); pick() and place() themselves are refused on sixdof."""
        if not isinstance(value, str):
            raise SixdofCommanderError(f"support surface name must be a string, got {value!r}")
        self._support_surface = value

    def get_support_surface_name(self) -> str:
        """The support surface name set (sixdof extension, for symmetry)."""
        return self._support_surface
