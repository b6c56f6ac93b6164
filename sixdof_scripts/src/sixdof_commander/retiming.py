"""MoveGroup's time parameterization: retime_trajectory (the core's iterative parabolic parameterization through
sixdof_core's bindings, time-optimal through move_group's retime_trajectory service) and the joint limits it reads."""

from __future__ import annotations

import math

import numpy as np
import rospy
from moveit_msgs.msg import RobotState, RobotTrajectory
from trajectory_msgs.msg import JointTrajectoryPoint

import sixdof_core

from ._ros import resolve
from .exceptions import SixdofCommanderError
from .goals import check_number, check_scaling_factor
from .move_group_base import MoveGroupContext

RETIME_ALGORITHMS = ("iterative_time_parameterization", "time_optimal_trajectory_generation")


class Retiming:
    """MoveGroupCommander.retime_trajectory, on the context MoveGroup hands it (the robot model, the connections to
    move_group, the namespace of its parameters)."""

    def __init__(self, context: MoveGroupContext) -> None:
        self._context = context

    def retime_trajectory(
        self,
        ref_state_in: RobotState,
        traj_in: RobotTrajectory,
        velocity_scaling_factor: float = 1.0,
        acceleration_scaling_factor: float = 1.0,
        algorithm: str = "iterative_time_parameterization",
    ) -> RobotTrajectory:
        """The trajectory's path re-timed for these scaling factors of the joint limits (robot_description_planning,
        else the URDF's velocity limits), starting and ending at rest. 'iterative_time_parameterization' is the
        core's iterative parabolic parameterization (one point per input point), computed in this process;
        'time_optimal_trajectory_generation' is move_group's time-optimal parameterization (the one
        every plan gets), through its retime_trajectory service. A failure raises SixdofCommanderError."""
        if algorithm not in RETIME_ALGORITHMS:
            raise SixdofCommanderError(
                f"retime_trajectory: unknown algorithm '{algorithm}'; known: {list(RETIME_ALGORITHMS)}"
            )
        if not isinstance(ref_state_in, RobotState) or not isinstance(traj_in, RobotTrajectory):
            raise SixdofCommanderError("retime_trajectory needs a RobotState and a RobotTrajectory")
        velocity = check_scaling_factor(velocity_scaling_factor, "velocity_scaling_factor")
        acceleration = check_scaling_factor(acceleration_scaling_factor, "acceleration_scaling_factor")
        if algorithm == "time_optimal_trajectory_generation":
            return self._retime_time_optimal(traj_in, velocity, acceleration)
        names = list(traj_in.joint_trajectory.joint_names)
        points = traj_in.joint_trajectory.points
        if not names or not points:
            raise SixdofCommanderError("retime_trajectory: the trajectory has no joints or no points")
        for i, point in enumerate(points):
            if len(point.positions) != len(names):
                raise SixdofCommanderError(
                    f"retime_trajectory: point {i} has {len(point.positions)} positions for {len(names)} joints"
                )
        path = np.array([[check_number(v, f"point {i} position") for v in p.positions] for i, p in enumerate(points)])
        max_velocity, max_acceleration = self._joint_limits(names)
        options = sixdof_core.TimeParameterizationOptions(max_velocity, max_acceleration, velocity, acceleration)
        retimed = sixdof_core.compute_iterative_parabolic_trajectory(names, path, options)
        if not retimed.ok:
            raise SixdofCommanderError(f"retime_trajectory: {retimed.message}")
        timed = retimed.trajectory
        result = RobotTrajectory()
        result.joint_trajectory.header = traj_in.joint_trajectory.header
        result.joint_trajectory.joint_names = names
        for t, q, v, a in zip(timed.times, path, timed.velocities, timed.accelerations, strict=True):
            result.joint_trajectory.points.append(
                JointTrajectoryPoint(
                    positions=list(q),
                    velocities=list(v),
                    accelerations=list(a),
                    time_from_start=rospy.Duration.from_sec(float(t)),
                )
            )
        return result

    def _retime_time_optimal(
        self, trajectory: RobotTrajectory, velocity: float, acceleration: float
    ) -> RobotTrajectory:
        retimed, outcome = self._context.clients.retime(trajectory, velocity, acceleration)
        if retimed is None:
            raise SixdofCommanderError(f"retime_trajectory: move_group's retime_trajectory failed: {outcome}")
        return retimed

    def _joint_limits(self, names: list[str]) -> tuple[list[float], list[float]]:
        """Velocity and acceleration limits of the joints, as move_group reads them (MoveIt's joint_limits)."""
        param = resolve(self._context.ns, "robot_description_planning/joint_limits")
        limits = rospy.get_param(param, {})
        velocities, accelerations = [], []
        for name in names:
            joints = self._context.robot.joints
            if name not in joints:
                raise SixdofCommanderError(f"retime_trajectory: '{name}' is not a joint of the robot")
            entry = limits.get(name, {}) if isinstance(limits, dict) else {}
            velocity = entry.get("max_velocity") if entry.get("has_velocity_limits", True) else None
            velocity = velocity if velocity is not None else joints[name].velocity
            acceleration = entry.get("max_acceleration") if entry.get("has_acceleration_limits", False) else None
            for value, what in ((velocity, "velocity"), (acceleration, "acceleration")):
                if value is None or not math.isfinite(float(value)) or float(value) <= 0.0:
                    raise SixdofCommanderError(
                        f"retime_trajectory: joint '{name}' has no {what} limit in "
                        f"'{rospy.resolve_name(param)}' (or the URDF)"
                    )
            velocities.append(float(velocity))
            accelerations.append(float(acceleration))
        return velocities, accelerations
