"""The commander's kinematics on sixdof_core's bindings: forward kinematics, the Jacobian and random joint values
come from the core's RobotModel and RobotState (the C++ model move_group plans with), built from the same
robot_description and robot_description_semantic parameters move_group read (`parameter_kinematics`, read on first
use); unit tests build it from files. Clamping a value into a joint's limits (`bounded`) is plain arithmetic."""

from __future__ import annotations

import functools
import math
import secrets
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import rospy

import sixdof_core

from ._ros import resolve
from .exceptions import SixdofCommanderError
from .robot_model import Joint


class CoreKinematics:
    """A sixdof_core RobotModel and the queries the commander makes of it: link poses, Jacobians, random values."""

    def __init__(self, urdf: str, srdf: str) -> None:
        """From URDF and SRDF XML text; SixdofCommanderError names what the core could not read."""
        try:
            self._model = sixdof_core.RobotModel(urdf, srdf)
        except ValueError as err:
            raise SixdofCommanderError(f"the core cannot read the robot description: {err}") from None
        self._sampler = sixdof_core.StateSampler(self._model, seed=secrets.randbits(64))

    @classmethod
    def from_parameters(cls, ns: str = "") -> CoreKinematics:
        """From the robot_description and robot_description_semantic parameters (move_group's, in namespace ns)."""
        texts = []
        for name in ("robot_description", "robot_description_semantic"):
            param = resolve(ns, name)
            text = rospy.get_param(param, None)
            if not isinstance(text, str) or not text:
                raise SixdofCommanderError(f"parameter '{rospy.resolve_name(param)}' holds no robot description")
            texts.append(text)
        return cls(*texts)

    def _state(self, positions: Mapping[str, float]) -> sixdof_core.RobotState:
        """A state at the model's default positions with these active joints set."""
        state = sixdof_core.RobotState(self._model)
        try:
            state.set_joint_positions(dict(positions))
        except ValueError as err:
            raise SixdofCommanderError(str(err)) from None
        return state

    def link_pose(self, link: str, positions: Mapping[str, float]) -> np.ndarray:
        """4x4 pose of `link` in the root link, the named active joints at these positions (others at default)."""
        state = self._state(positions)
        try:
            return state.link_pose(link)
        except ValueError as err:
            raise SixdofCommanderError(str(err)) from None

    def jacobian(
        self, group: str, link: str, positions: Mapping[str, float], reference_point: Sequence[float] = (0.0, 0.0, 0.0)
    ) -> np.ndarray:
        """Geometric Jacobian (6 x the group's active joints; rows vx, vy, vz, wx, wy, wz in the root frame) of the
        point `reference_point`, fixed in `link`'s frame, as MoveIt's getJacobian (mimic joints add to their
        source's column)."""
        state = self._state(positions)
        try:
            return state.jacobian(group, link, np.asarray(reference_point, dtype=float))
        except ValueError as err:
            raise SixdofCommanderError(f"get_jacobian_matrix: {err}") from None

    def random_group_values(self, group: str) -> list[float]:
        """Uniformly random values of the group's active joints within their limits ([-pi, pi] for continuous
        joints), in the group's order."""
        state = sixdof_core.RobotState(self._model)
        state.set_to_random_positions(self._sampler, group)
        return [float(v) for v in state.group_positions(group)]


def parameter_kinematics(ns: str = "") -> Callable[[], CoreKinematics]:
    """A function returning the CoreKinematics of move_group's parameters in namespace ns, read on its first call
    (so that a MoveGroup that never asks for kinematics never reads them)."""
    return functools.cache(lambda: CoreKinematics.from_parameters(ns))


def bounded(joint: Joint, value: float) -> float:
    """value clamped into the joint's limits (continuous joints: wrapped into [-pi, pi])."""
    if joint.type == "continuous":
        return (value + math.pi) % (2.0 * math.pi) - math.pi
    return min(max(value, joint.lower), joint.upper)
