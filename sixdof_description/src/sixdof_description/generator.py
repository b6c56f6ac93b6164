"""Generates meshes, URDF, SRDF and MoveIt/controller YAML of the sixdof arm from config/design.yaml, with its tool:
the two-finger gripper (urdf/sixdof.urdf, config/) or the suction cup (urdf/sixdof_suction.urdf, config/suction/).

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
from sixdof_description.robot_design import TOOLS, Robot, design_robot, load_design, stl_bytes, tool_links
from sixdof_description.urdf_writer import render_urdf
from sixdof_setup_assistant.generator import config_files

CONFIG_FILES = ("kinematics.yaml", "joint_limits.yaml", "controllers.yaml", "hardware.yaml", "setup_answers.yaml",
                "grasping.yaml")


def config_dir(tool: str) -> str:
    """Where a tool's config files are: config/ for the two-finger gripper, config/suction/ for the suction cup."""
    return "config" if tool == TOOLS[0] else f"config/{tool}"


def generated_files(tool: str = TOOLS[0]) -> tuple[str, ...]:
    """The package-relative paths the generator writes for the arm with that tool."""
    name = "sixdof" if tool == TOOLS[0] else f"sixdof_{tool}"
    return (
        f"urdf/{name}.urdf",
        f"{config_dir(tool)}/{name}.srdf",
        *[f"{config_dir(tool)}/{file}" for file in CONFIG_FILES],
        *[f"meshes/visual/{link}.stl" for link in tool_links(tool)],
        *[f"meshes/collision/{link}.stl" for link in tool_links(tool)],
    )


GENERATED_FILES = generated_files()


def build_robot(design: dict, tool: str | None = None) -> Robot:
    """The designed robot with the tool (default: the design's) and its named states."""
    robot = design_robot(design, tool)
    robot.states = solve_named_states(robot)
    return robot


def generate_files(design_path: Path, previous_srdf: str | None, tool: str | None = None) -> dict:
    """All generated files of the arm with the tool (default: the design's `tool`) as {package-relative path:
    bytes}."""
    try:
        robot = build_robot(load_design(design_path), tool)
    except KeyError as missing:
        raise cad.DesignError(f"{design_path}: missing design parameter {missing}") from missing
    config = config_dir(robot.tool)
    files = {
        f"urdf/{robot.name}.urdf": render_urdf(robot).encode(),
        f"{config}/setup_answers.yaml": render_setup_answers(robot).encode(),
    }
    for name in robot.link_names:
        files[f"meshes/visual/{name}.stl"] = stl_bytes(robot.links[name].visual)
        files[f"meshes/collision/{name}.stl"] = stl_bytes(robot.links[name].collision)
    written = render_config(files, previous_srdf, robot)
    written[f"{config}/controllers.yaml"] = render_controllers(robot, written[f"{config}/controllers.yaml"])
    files.update({rel: text.encode() for rel, text in written.items()})
    return files


def render_config(files: dict, previous_srdf: str | None, robot: Robot) -> dict:
    """The config files the setup assistant writes for these files (the URDF, its meshes and the answers), in the
    tool's config folder, read from a copy of the package in a temporary folder so that the URDF's package://
    meshes are these ones."""
    config = config_dir(robot.tool)
    with tempfile.TemporaryDirectory(prefix="sixdof_description.") as tmp:
        package = Path(tmp) / "sixdof_description"
        write_files(files, package)
        (package / "package.xml").write_text('<package format="3"><name>sixdof_description</name></package>\n')
        written = config_files(str(package / "urdf" / f"{robot.name}.urdf"),
                               str(package / config / "setup_answers.yaml"), previous_srdf)
    written = {f"{config}/{rel.removeprefix('config/')}": text for rel, text in written.items()}
    missing = sorted(set(generated_files(robot.tool)) - set(files) - set(written))
    if missing:
        raise cad.DesignError(f"the setup assistant wrote no {', '.join(missing)} for the generated URDF")
    return written


def write_files(files: dict, out_dir: Path) -> None:
    for rel, data in files.items():
        path = out_dir / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
