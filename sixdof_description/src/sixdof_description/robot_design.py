"""The sixdof arm built from config/design.yaml: link solids and their mass properties, and joints (the named states
are solved by core_model.py, with sixdof_core's IK)."""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
import yaml

from sixdof_description import cad

ARM_JOINTS = ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6")
GRIPPER_JOINTS = ("finger1_joint", "finger2_joint")
ARM_LINKS = ("base_link", "link1", "link2", "link3", "link4", "link5", "link6")
LINKS = (*ARM_LINKS, "palm", "finger1", "finger2")
ROOT_LINK = "base_link"
# design.yaml's `tool`: the two-finger gripper (default) or a suction cup on the flange (design.yaml `suction_cup`).
TOOLS = ("two_finger", "suction")
SUCTION_LINKS = (*ARM_LINKS, "cup")


def tool_links(tool: str) -> tuple[str, ...]:
    """The links of the arm with that tool, parents first."""
    return SUCTION_LINKS if tool == "suction" else LINKS


def tool_joints(tool: str) -> tuple[str, ...]:
    """The tool's moving joints (none for the suction cup)."""
    return () if tool == "suction" else GRIPPER_JOINTS


@dataclass(frozen=True)
class JointSpec:
    """One URDF joint of the design (origin in the parent link, axis in the child link)."""

    name: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    axis: tuple[float, float, float]
    joint_type: str  # revolute | prismatic | fixed
    lower: float = 0.0
    upper: float = 0.0


@dataclass
class LinkModel:
    name: str
    visual: trimesh.Trimesh
    collision: trimesh.Trimesh
    mass: float
    com: np.ndarray
    inertia: np.ndarray  # about the centre of mass, link-frame axes


@dataclass
class Robot:
    design: dict
    joints: list[JointSpec]  # every URDF joint, parents before children
    joint_params: dict  # per movable joint: velocity, effort, acceleration, damping, friction
    links: dict
    tcp_z: float
    states: dict  # named arm states: name -> arm joint values (core_model.solve_named_states)
    tool: str = "two_finger"  # TOOLS

    @property
    def link_names(self) -> tuple[str, ...]:
        return tool_links(self.tool)

    @property
    def tool_joints(self) -> tuple[str, ...]:
        return tool_joints(self.tool)

    @property
    def name(self) -> str:
        """The URDF robot's name: the design's, with `_suction` for the suction variant."""
        return self.design["robot_name"] + ("_suction" if self.tool == "suction" else "")


def load_design(path: Path) -> dict:
    with open(path, encoding="utf-8") as f:
        design = yaml.safe_load(f)
    required = ("robot_name", "density", "joints", "links", "gripper", "mesh", "colours", "friction",
                "controllers", "named_states", "gripper_states")
    missing = [k for k in required if k not in design]
    if missing:
        raise cad.DesignError(f"{path}: missing design parameters {missing}")
    if list(design["joints"]) != list(ARM_JOINTS):
        raise cad.DesignError(f"{path}: joints must be exactly {list(ARM_JOINTS)} in order")
    if float(design["density"]) <= 0.0:
        raise cad.DesignError(f"{path}: density must be positive")
    tool = design.get("tool", TOOLS[0])
    if tool not in TOOLS:
        raise cad.DesignError(f"{path}: tool must be one of {', '.join(TOOLS)}, got '{tool}'")
    return design


def check_tool(design: dict, tool: str) -> None:
    """The design parameters the tool needs are there (suction: `suction_cup`)."""
    if tool not in TOOLS:
        raise cad.DesignError(f"tool must be one of {', '.join(TOOLS)}, got '{tool}'")
    if tool == "suction":
        cup = design.get("suction_cup")
        if not isinstance(cup, dict):
            raise cad.DesignError("tool suction needs the design's suction_cup parameters")
        for key in ("radius", "length", "max_payload"):
            if not float(cup[key]) > 0.0:
                raise cad.DesignError(f"suction_cup.{key} must be positive, got {cup[key]}")


def mass_properties(mesh: trimesh.Trimesh, density: float) -> tuple[float, np.ndarray, np.ndarray]:
    if not mesh.is_volume:
        raise cad.DesignError("a link solid is not a closed volume; cannot compute its mass properties")
    m = trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=False)
    m.density = density
    # Snapped to absolute grids (1 ug, 1 nm, 1e-12 kg m^2) so summation noise such as 1e-20 products of
    # inertia never reaches the committed URDF.
    return round(float(m.mass), 9), np.round(m.center_mass, 9) + 0.0, np.round(m.moment_inertia, 12) + 0.0


def gripper_offsets(design: dict, tool: str = TOOLS[0]) -> dict:
    if tool == "suction":
        # The cup stands on link6's flange; its face (the tcp) is its far end.
        flange = float(design["links"]["link6"]["flange_t"])
        return {"cup_z": flange, "tcp_z": round(flange + float(design["suction_cup"]["length"]), 9)}
    g = design["gripper"]
    pad_lo, pad_hi = cad.pad_span(g["finger"], g["pad"])
    palm_z = float(g["palm"]["offset_z"])
    finger_z = float(g["palm"]["height_z"])
    tcp_z = round(palm_z + finger_z + (pad_lo + pad_hi) / 2.0, 9)
    return {"palm_z": palm_z, "finger_z": finger_z, "tcp_z": tcp_z}


def build_links(design: dict, tool: str = TOOLS[0]) -> dict:
    mesh_p = design["mesh"]
    fine = cad.Resolution(int(mesh_p["visual_segments"]), int(mesh_p["fillet_segments"]), True)
    coarse = cad.Resolution(int(mesh_p["collision_segments"]), 1, False)
    lp, g, j = design["links"], design["gripper"], design["joints"]

    def solids(res: cad.Resolution) -> dict:
        arm = {
            "base_link": cad.base_link(lp["base_link"], j["joint1"]["xyz"][2], res),
            "link1": cad.link1(lp["link1"], j["joint2"]["xyz"][2], res),
            "link2": cad.link2(lp["link2"], j["joint3"]["xyz"][2], res),
            "link3": cad.link3(lp["link3"], j["joint4"]["xyz"][0], res),
            "link4": cad.link4(lp["link4"], j["joint5"]["xyz"][0], res),
            "link5": cad.link5(lp["link5"], j["joint6"]["xyz"][0], res),
            "link6": cad.link6(lp["link6"], res),
        }
        if tool == "suction":
            return {**arm, "cup": cad.cup(design["suction_cup"], res)}
        f1 = cad.finger(g["finger"], g["pad"], res)
        return {
            **arm,
            "palm": cad.palm(g["palm"], res),
            "finger1": f1,
            "finger2": cad.mirror_finger(f1),
        }

    visual, rough = solids(fine), solids(coarse)
    density = float(design["density"])
    links = {}
    for name in tool_links(tool):
        vis = cad.quantize(visual[name])
        reloaded = trimesh.load(io.BytesIO(stl_bytes(vis)), file_type="stl")
        if not reloaded.is_watertight:
            raise cad.DesignError(f"{name}: the exported visual mesh is not closed (touching CSG operands?)")
        mass, com, inertia = mass_properties(vis, density)
        links[name] = LinkModel(name, vis, cad.collision_hull(rough[name]), mass, com, inertia)
    return links


def joint_specs(design: dict, offsets: dict, tool: str = TOOLS[0]) -> tuple[list[JointSpec], dict]:
    specs, params = [], {}
    for name in ARM_JOINTS:
        p = design["joints"][name]
        specs.append(JointSpec(name, tuple(p["xyz"]), tuple(p["rpy"]), tuple(p["axis"]), "revolute",
                               float(p["lower"]), float(p["upper"])))
        params[name] = p
    if tool == "suction":
        specs.append(JointSpec("cup_joint", (0.0, 0.0, offsets["cup_z"]), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), "fixed"))
        specs.append(JointSpec("tcp_joint", (0.0, 0.0, offsets["tcp_z"]), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), "fixed"))
        return specs, params
    fj = design["gripper"]["finger_joint"]
    specs.append(JointSpec("palm_joint", (0.0, 0.0, offsets["palm_z"]), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), "fixed"))
    for name, axis in (("finger1_joint", (0.0, 1.0, 0.0)), ("finger2_joint", (0.0, -1.0, 0.0))):
        specs.append(JointSpec(name, (0.0, 0.0, offsets["finger_z"]), (0.0, 0.0, 0.0), axis, "prismatic",
                               float(fj["lower"]), float(fj["upper"])))
        params[name] = fj
    specs.append(JointSpec("tcp_joint", (0.0, 0.0, offsets["tcp_z"]), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), "fixed"))
    return specs, params


JOINT_LINKS = {
    "joint1": ("base_link", "link1"), "joint2": ("link1", "link2"), "joint3": ("link2", "link3"),
    "joint4": ("link3", "link4"), "joint5": ("link4", "link5"), "joint6": ("link5", "link6"),
    "palm_joint": ("link6", "palm"), "finger1_joint": ("palm", "finger1"), "finger2_joint": ("palm", "finger2"),
    "tcp_joint": ("link6", "tcp"), "cup_joint": ("link6", "cup"),
}


def design_robot(design: dict, tool: str | None = None) -> Robot:
    """The robot with the tool (default: the design's `tool`) and its links and joints; its named states are solved
    afterwards (core_model.solve_named_states)."""
    tool = tool or design.get("tool", TOOLS[0])
    check_tool(design, tool)
    offsets = gripper_offsets(design, tool)
    specs, params = joint_specs(design, offsets, tool)
    return Robot(design, specs, params, build_links(design, tool), offsets["tcp_z"], {}, tool)


def stl_bytes(mesh: trimesh.Trimesh) -> bytes:
    return trimesh.exchange.stl.export_stl(mesh)
