"""What MoveGroup and its parts share: the context MoveGroup hands its parts, serving a part's methods as
MoveGroup's, and the refusal of the MoveGroupCommander methods sixdof does not offer."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from moveit_msgs.msg import Constraints

from .exceptions import MoveItCommanderException, SixdofCommanderError
from .goals import GoalBuilder
from .kinematics import CoreKinematics
from .move_group_clients import MoveGroupClients
from .robot_model import Group, RobotDescription
from .state_monitor import StateMonitor


class PartMethod:
    """A method of a class served by one of the parts it holds: on an instance, the bound method of the part kept in
    `attribute`; on the class, the part's function (its signature and docstring, for help() and inspect)."""

    def __init__(self, attribute: str, function: Callable[..., object]) -> None:
        self._attribute = attribute
        self._function = function
        self.__doc__ = function.__doc__

    def __get__(self, instance: object, owner: type | None = None) -> Callable[..., object]:
        if instance is None:
            return self._function
        return getattr(getattr(instance, self._attribute), self._function.__name__)


def served_by(**parts: type | tuple[type, tuple[str, ...]]) -> Callable[[type], type]:
    """Class decorator: each public method of each part class (keyword: the attribute the decorated class keeps that
    part's instance in), or the methods named with it (a (class, names) pair), becomes a method of the decorated
    class, served by that instance. A name the class or another part already has raises TypeError."""

    def decorate(cls: type) -> type:
        for attribute, served in parts.items():
            part, names = served if isinstance(served, tuple) else (served, None)
            for name, function in vars(part).items():
                if name.startswith("_") or not callable(function) or (names is not None and name not in names):
                    continue
                if hasattr(cls, name):
                    raise TypeError(f"{cls.__name__}.{name}: {part.__name__} and another part both define it")
                setattr(cls, name, PartMethod(attribute, function))
        return cls

    return decorate


@dataclass(frozen=True)
class MoveGroupContext:
    """What MoveGroup hands its parts: the namespace of move_group and its parameters, the group and the robot model,
    the planning frame, the request builder (targets and parameters), the connections to move_group, the current joint
    values and the core's kinematics (loaded on the first call)."""

    ns: str
    group: Group
    robot: RobotDescription
    planning_frame: str
    goal: GoalBuilder
    clients: MoveGroupClients
    state: StateMonitor
    kinematics: Callable[[], CoreKinematics]


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
