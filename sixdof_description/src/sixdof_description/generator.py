"""Generates meshes, URDF, SRDF and MoveIt/controller YAML of the sixdof arm from config/design.yaml.

Deterministic: the same design.yaml (and previous SRDF) always gives byte-identical files.

The parts: robot_design.py (solids, joints), core_model.py (the arm as sixdof_core reads it: named states by IK, joint-
space inertia), urdf_writer.py, config_writer.py (the setup assistant's answers, the controllers' gains) and
formatting.py. The SRDF, kinematics, joint limits, controllers, hardware.yaml and grasping.yaml are the setup
assistant's (sixdof_setup_assistant.generator.config_files) for the generated URDF, meshes and answers.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from sixdof_description import cad
from sixdof_description.config_writer import render_controllers, render_setup_answers
from sixdof_description.core_model import solve_named_states
from sixdof_description.robot_design import LINKS, Robot, design_robot, load_design, stl_bytes
from sixdof_description.urdf_writer import render_urdf
from sixdof_setup_assistant.generator import config_files

GENERATED_FILES = (
    "urdf/sixdof.urdf",
    "config/sixdof.srdf",
    "config/kinematics.yaml",
    "config/joint_limits.yaml",
    "config/controllers.yaml",
    "config/hardware.yaml",
    "config/setup_answers.yaml",
    "config/grasping.yaml",
    *[f"meshes/visual/{name}.stl" for name in LINKS],
    *[f"meshes/collision/{name}.stl" for name in LINKS],
)


def build_robot(design: dict) -> Robot:
    """The designed robot with its named states."""
    robot = design_robot(design)
    robot.states = solve_named_states(robot)
    return robot


def generate_files(design_path: Path, previous_srdf: str | None) -> dict:
    """All generated files as {package-relative path: bytes}."""
    try:
        robot = build_robot(load_design(design_path))
    except KeyError as missing:
        raise cad.DesignError(f"{design_path}: missing design parameter {missing}") from missing
    files = {
        "urdf/sixdof.urdf": render_urdf(robot).encode(),
        "config/setup_answers.yaml": render_setup_answers(robot).encode(),
    }
    for name in LINKS:
        files[f"meshes/visual/{name}.stl"] = stl_bytes(robot.links[name].visual)
        files[f"meshes/collision/{name}.stl"] = stl_bytes(robot.links[name].collision)
    config = render_config(files, previous_srdf)
    config["config/controllers.yaml"] = render_controllers(robot, config["config/controllers.yaml"])
    files.update({rel: text.encode() for rel, text in config.items()})
    return files


def render_config(files: dict, previous_srdf: str | None) -> dict:
    """The config files the setup assistant writes for these files (the URDF, its meshes and the answers),
    read from a copy of the package in a temporary folder so that the URDF's package:// meshes are these ones."""
    with tempfile.TemporaryDirectory(prefix="sixdof_description.") as tmp:
        package = Path(tmp) / "sixdof_description"
        write_files(files, package)
        (package / "package.xml").write_text('<package format="3"><name>sixdof_description</name></package>\n')
        config = config_files(str(package / "urdf" / "sixdof.urdf"), str(package / "config" / "setup_answers.yaml"),
                              previous_srdf)
    missing = sorted(set(GENERATED_FILES) - set(files) - set(config))
    if missing:
        raise cad.DesignError(f"the setup assistant wrote no {', '.join(missing)} for the generated URDF")
    return config


def write_files(files: dict, out_dir: Path) -> None:
    for rel, data in files.items():
        path = out_dir / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
