"""The answers file of `setup_assistant --answers`: every choice the setup assistant would otherwise infer.

All keys are optional; an unknown key or a bad value is an error naming it (AnswersError)::

    name: my_robot_sixdof_config    # package name (the --name option wins)
    density: 10000                  # self-collision samples (the --density option wins)
    seed: 0                         # sampling seed (the --seed option wins)
    planning_frame: world           # parent frame of the virtual joint (none when the root link has this name)
    arm:
      group: arm                    # group name
      base_link: base_link          # chain base (default: the root link)
      tip_link: link6               # chain tip (default: the child of the arm's last joint)
      joints: [j1, j2]              # instead of base/tip: a joint list (the group is then not a chain)
      solver: analytic              # analytic | numeric | kdl (default: analytic where the closed form fits)
      controller: arm_controller    # controller name
      controller_type: position_controllers/JointTrajectoryController
    gripper:                        # `gripper: none` for an arm without one
      group: gripper
      joints: [finger1_joint, finger2_joint]
      controller: gripper_controller
      controller_type: position_controllers/JointTrajectoryController
    end_effector: {name: hand, parent_link: link6}
    named_states:                   # group -> state -> joint -> value (radians / metres)
      arm: {home: {joint1: 0.0}}    # replaces the inferred `home`; give every joint of the group
      gripper: {open: {finger1_joint: 0.04}, close: {finger1_joint: 0.0}}
    acceleration_limits: {joint1: 4.0}   # per joint; others default to 2 x max_velocity
"""

from __future__ import annotations

import math
from typing import Any

import yaml

SOLVERS = ("analytic", "numeric", "kdl")

_SCHEMA: dict[str, Any] = {
    "name": str,
    "density": int,
    "seed": int,
    "planning_frame": str,
    "arm": {"group": str, "base_link": str, "tip_link": str, "joints": list, "solver": str, "controller": str,
            "controller_type": str},
    "gripper": {"group": str, "joints": list, "controller": str, "controller_type": str},
    "end_effector": {"name": str, "parent_link": str},
    "named_states": dict,
    "acceleration_limits": dict,
}


class AnswersError(Exception):
    """An answers file that cannot be used; the message names the file and the key."""


def _check(value: Any, schema: Any, where: str, source: str) -> None:
    if isinstance(schema, dict):
        if not isinstance(value, dict):
            raise AnswersError(f"{source}: '{where}' must be a mapping")
        for key, item in value.items():
            if key not in schema:
                known = ", ".join(sorted(schema))
                raise AnswersError(f"{source}: unknown key '{where + '.' if where else ''}{key}' (known: {known})")
            _check(item, schema[key], f"{where + '.' if where else ''}{key}", source)
        return
    if schema is int and (isinstance(value, bool) or not isinstance(value, int)):
        raise AnswersError(f"{source}: '{where}' must be a whole number, got {value!r}")
    if schema is str and (not isinstance(value, str) or not value):
        raise AnswersError(f"{source}: '{where}' must be a non-empty string, got {value!r}")
    if schema is list and (not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value)):
        raise AnswersError(f"{source}: '{where}' must be a non-empty list of joint names, got {value!r}")
    if schema is dict and not isinstance(value, dict):
        raise AnswersError(f"{source}: '{where}' must be a mapping, got {value!r}")


def _number(value: Any, where: str, source: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise AnswersError(f"{source}: '{where}' must be a finite number, got {value!r}")
    return float(value)


def load_answers(path: str | None) -> dict[str, Any]:
    """The validated answers (an empty mapping without a file). Raises AnswersError naming the problem."""
    if not path:
        return {}
    try:
        with open(path, encoding="utf-8") as file:
            data = yaml.safe_load(file)
    except OSError as error:
        raise AnswersError(f"{path}: cannot read: {error.strerror}") from None
    except yaml.YAMLError as error:
        raise AnswersError(f"{path}: not valid YAML: {' '.join(str(error).split())}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise AnswersError(f"{path}: must be a mapping of answers, got {type(data).__name__}")
    no_gripper = data.get("gripper") == "none"
    _check({k: v for k, v in data.items() if not (k == "gripper" and no_gripper)}, _SCHEMA, "", path)
    arm = data.get("arm", {})
    if "joints" in arm and ("base_link" in arm or "tip_link" in arm):
        raise AnswersError(f"{path}: 'arm' takes either joints or base_link/tip_link, not both")
    if "solver" in arm and arm["solver"] not in SOLVERS:
        raise AnswersError(f"{path}: 'arm.solver' must be one of {', '.join(SOLVERS)}, got {arm['solver']!r}")
    for key in ("density",):
        if key in data and data[key] <= 0:
            raise AnswersError(f"{path}: '{key}' must be > 0, got {data[key]}")
    if "seed" in data and data["seed"] < 0:
        raise AnswersError(f"{path}: 'seed' must be >= 0, got {data['seed']}")
    for group, states in data.get("named_states", {}).items():
        if not isinstance(states, dict):
            raise AnswersError(f"{path}: 'named_states.{group}' must map state names to joint values")
        for state, values in states.items():
            if not isinstance(values, dict) or not values:
                raise AnswersError(f"{path}: 'named_states.{group}.{state}' must map joint names to values")
            for joint, value in values.items():
                _number(value, f"named_states.{group}.{state}.{joint}", path)
    for joint, value in data.get("acceleration_limits", {}).items():
        if _number(value, f"acceleration_limits.{joint}", path) <= 0:
            raise AnswersError(f"{path}: 'acceleration_limits.{joint}' must be > 0, got {value}")
    return data
