"""The answers file of `setup_assistant --answers`: every choice the setup assistant would otherwise infer.

All keys are optional; an unknown key or a bad value is an error naming it (AnswersError)::

    name: my_robot_sixdof_config    # package name (the --name option wins)
    density: 10000                  # self-collision samples (the --density option wins)
    seed: 0                         # sampling seed (the --seed option wins)
    default_density: 1000           # kg/m^3 of the inertias computed for moving links without a usable one
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
    grasping:                       # the gripper's grasp geometry (default: inferred from its links' shapes)
      tcp: {parent_link: link6, xyz: [0, 0, 0.113], rpy: [0, 0, 0]}   # refused when a link `tcp` exists
      pad_links: [finger1, finger2]
      closing_direction: [0, 1, 0]  # in the end effector's parent link frame
      max_opening: 0.08             # m between the pads
      grasp_fix: {palm_link: link6, gripper_links: [finger1, finger2], forces_angle_tolerance: 120,
                  update_rate: 5, grip_count_threshold: 5, max_grip_count: 10, release_tolerance: 0.005,
                  disable_collisions_on_attach: false}
    suction:                        # a suction tool instead of a gripper (default: inferred, see suction.py)
      cup_link: cup                 # the cup, fixed below the arm's tip; its TCP is at the cup's face
      max_payload: 0.5              # kg; tilt_tolerance: rad in (0, pi/2]; contact_distance: m in (0, 0.02]
"""

from __future__ import annotations

import math
from typing import Any

import yaml

SOLVERS = ("analytic", "numeric", "kdl")
# gazebo_grasp_fix's own defaults (docs/your_own_arm.md), written into grasping.yaml unless the answers give others.
GRASP_FIX_DEFAULTS: dict[str, Any] = {"forces_angle_tolerance": 120.0, "update_rate": 5.0, "grip_count_threshold": 5,
                                      "max_grip_count": 10, "release_tolerance": 0.005,
                                      "disable_collisions_on_attach": False}

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
    "default_density": float,
    "grasping": {
        "tcp": {"parent_link": str, "xyz": "vector", "rpy": "vector"},
        "pad_links": list,
        "closing_direction": "vector",
        "max_opening": float,
        "grasp_fix": {"palm_link": str, "gripper_links": list, "forces_angle_tolerance": float, "update_rate": float,
                      "grip_count_threshold": int, "max_grip_count": int, "release_tolerance": float,
                      "disable_collisions_on_attach": bool},
    },
    "suction": {"cup_link": str, "max_payload": float, "tilt_tolerance": float, "contact_distance": float},
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
    if schema is float:
        _number(value, where, source)
    if schema == "vector" and (not isinstance(value, list) or len(value) != 3):
        raise AnswersError(f"{source}: '{where}' must be a list of 3 numbers, got {value!r}")
    if schema == "vector":
        for number in value:
            _number(number, where, source)
    if schema is bool and not isinstance(value, bool):
        raise AnswersError(f"{source}: '{where}' must be true or false, got {value!r}")
    if schema is str and (not isinstance(value, str) or not value):
        raise AnswersError(f"{source}: '{where}' must be a non-empty string, got {value!r}")
    if schema is list and (not isinstance(value, list) or not value or not all(isinstance(v, str) for v in value)):
        raise AnswersError(f"{source}: '{where}' must be a non-empty list of names, got {value!r}")
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
    _check_grasping(data, path)
    return data


def _check_grasping(data: dict[str, Any], path: str) -> None:
    """The checks of the density and grasping keys that the schema cannot express."""
    for key in ("default_density", "grasping.max_opening"):
        section, _, name = key.rpartition(".")
        value = (data.get(section, {}) if section else data).get(name)
        if value is not None and value <= 0:
            raise AnswersError(f"{path}: '{key}' must be > 0, got {value}")
    _check_suction(data, path)
    grasping = data.get("grasping", {})
    if data.get("gripper") == "none" and grasping:
        raise AnswersError(f"{path}: 'grasping' is given but 'gripper' is none")
    tcp = grasping.get("tcp")
    if tcp is not None and set(tcp) != {"parent_link", "xyz", "rpy"}:
        raise AnswersError(f"{path}: 'grasping.tcp' needs parent_link, xyz and rpy, got {sorted(tcp)}")
    pads = grasping.get("pad_links")
    if pads is not None and (len(pads) != 2 or pads[0] == pads[1]):
        raise AnswersError(f"{path}: 'grasping.pad_links' must name two different links, got {pads}")
    direction = grasping.get("closing_direction")
    if direction is not None and math.hypot(*direction) < 1e-9:
        raise AnswersError(f"{path}: 'grasping.closing_direction' must not be zero")
    fix = grasping.get("grasp_fix", {})
    if "forces_angle_tolerance" in fix and not 90 <= fix["forces_angle_tolerance"] <= 180:
        raise AnswersError(f"{path}: 'grasping.grasp_fix.forces_angle_tolerance' must be in [90, 180] degrees")
    for key in ("update_rate", "release_tolerance"):
        if key in fix and fix[key] <= 0:
            raise AnswersError(f"{path}: 'grasping.grasp_fix.{key}' must be > 0, got {fix[key]}")
    merged = {**GRASP_FIX_DEFAULTS, **fix}
    if not 0 <= merged["grip_count_threshold"] < merged["max_grip_count"]:
        raise AnswersError(f"{path}: 'grasping.grasp_fix' needs 0 <= grip_count_threshold < max_grip_count")


def _check_suction(data: dict[str, Any], path: str) -> None:
    """The suction keys' ranges (the simulator's, sixdof_sim/suction.h)."""
    if "suction" not in data:
        return
    suction = data["suction"]
    if "grasping" in data:
        raise AnswersError(f"{path}: 'grasping' is for a gripper with fingers; a suction tool's TCP is its cup's face")
    bounds = {"max_payload": (0.0, math.inf), "tilt_tolerance": (0.0, math.pi / 2), "contact_distance": (0.0, 0.02)}
    for key, (lower, upper) in bounds.items():
        if key in suction and not lower < suction[key] <= upper:
            raise AnswersError(f"{path}: 'suction.{key}' must be in ({lower:g}, {upper:g}], got {suction[key]}")
