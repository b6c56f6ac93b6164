"""A suction tool: a cup link rigidly fixed below the arm's tip (no moving joint between), its TCP at the cup's face,
and the simulator's vacuum settings (grasping.yaml's `suction:` section).

The rules, on the core's model description (`setup_assistant_core --describe`: the links' shapes, the joints'
origins; docs/your_own_arm.md "Suction tools"):
- the answers' `suction: {cup_link: L, ...}` names the cup; L must be below the arm's tip through fixed joints only.
- Without it, a robot with no moving joint below the arm's tip has a suction tool when exactly one link of the
  tool is a cup. The tool's outermost bodies are the links below the tip, reached through fixed joints only, that
  have collision (else visual) geometry and no such link below them. One of them is a cup when its name contains
  `cup`, `suction` or `vacuum` (any case); when none is named so, when its geometry is a single cylinder no longer
  than its diameter (a short cylinder). Two cups of the same kind are an error asking for `suction.cup_link`.
- The cup's face and axis: for a cylinder, the centre of its end farther from the arm tip's origin, the axis
  pointing out through that end (the approach); for other geometry, the cup link's origin and +z axis.
- The TCP is the link `tcp` at the face, z along the approach (its x axis the cup link's x, made square to z); a
  URDF link `tcp` fixed below the tip is used as it is. The simulator's cup frame is the TCP (`suction.cup_link:
  tcp`): its face is the plane through the frame's origin, +z out of the cup.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import yaml

from .infer import InferenceError, Plan

# The simulator's defaults (sixdof_sim/suction.h), written out so the package says what it runs with.
SUCTION_DEFAULTS: dict[str, Any] = {"max_payload": 0.5, "tilt_tolerance": 0.2, "contact_distance": 0.003}
CUP_NAME = re.compile(r"cup|suction|vacuum", re.IGNORECASE)
TCP_FRAME = "tcp"
FOUND = {"answers": "named in the answers", "name": "found by its name", "shape": "found by its shape"}


@dataclass
class SuctionTool:
    cup_link: str
    parent_link: str  # the arm's tip: the frame of the TCP and the approach
    tcp_xyz: list[float]
    tcp_rpy: list[float]
    approach: list[float]  # unit, in parent_link
    found_by: str  # answers | name | shape
    tcp_source: str  # cup face | link 'tcp' | answers
    settings: dict[str, Any] = field(default_factory=dict)  # max_payload, tilt_tolerance, contact_distance
    add_tcp_link: bool = True  # the URDF has no link `tcp`: the package's URDF gets one
    group: str = "gripper"  # the SRDF group of the cup (links only), the end effector's group
    controller: str = "gripper_controller"  # the vacuum: <controller>/gripper_cmd (the simulator serves it)


def _rotation(rpy: list[float]) -> np.ndarray:
    """URDF rpy (fixed axes x, y, z) as a rotation matrix."""
    r, p, y = rpy
    cx, sx, cy, sy, cz, sz = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
                     [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
                     [-sy, cy * sx, cy * cx]])


def _rpy(rotation: np.ndarray) -> list[float]:
    pitch = math.atan2(-rotation[2, 0], math.hypot(rotation[0, 0], rotation[1, 0]))
    if abs(math.cos(pitch)) < 1e-9:
        return [math.atan2(-rotation[1, 2], rotation[1, 1]), pitch, 0.0]
    return [math.atan2(rotation[2, 1], rotation[2, 2]), pitch, math.atan2(rotation[1, 0], rotation[0, 0])]


def _transform(entry: dict[str, Any]) -> np.ndarray:
    """4x4 transform of a joint's or a shape's origin (xyz, rpy) in the core's model description."""
    transform = np.eye(4)
    transform[:3, :3] = _rotation(entry["rpy"])
    transform[:3, 3] = entry["xyz"]
    return transform


class _Tool:
    """The links' shapes and the fixed joints of the core's model description (`setup_assistant_core
    --describe`: links with their collision, else visual, shapes; joints with their origins)."""

    def __init__(self, model: dict[str, Any]) -> None:
        self.links = {link["name"]: link for link in model["links"]}
        self.children: dict[str, list[dict[str, Any]]] = {name: [] for name in self.links}
        self.parent: dict[str, str] = {}
        for joint in model["joints"]:
            self.children[joint["parent"]].append(joint)
            self.parent[joint["child"]] = joint["parent"]

    def shapes(self, link: str) -> list[dict[str, Any]]:
        return self.links[link].get("shapes", [])

    def fixed_below(self, tip: str) -> dict[str, np.ndarray]:
        """Every link below tip through fixed joints only, with its pose in tip."""
        poses, stack = {}, [(tip, np.eye(4))]
        while stack:
            link, pose = stack.pop()
            for joint in self.children[link]:
                if joint["type"] == "fixed":
                    poses[joint["child"]] = pose @ _transform(joint)
                    stack.append((joint["child"], poses[joint["child"]]))
        return poses

    def below(self, link: str, other: str) -> bool:
        """Whether `other` hangs below `link`."""
        while other in self.parent:
            other = self.parent[other]
            if other == link:
                return True
        return False


def _short_cylinder(shapes: list[dict[str, Any]]) -> bool:
    return len(shapes) == 1 and shapes[0]["type"] == "cylinder" and shapes[0]["length"] <= 2.0 * shapes[0]["radius"]


def _infer_cup(tool: _Tool, below: dict[str, np.ndarray], tip: str) -> tuple[str, str] | None:
    """(cup link, name | shape) among the tool's outermost bodies, or None."""
    bodies = [link for link in below if tool.shapes(link)]
    outermost = [link for link in bodies if not any(tool.below(link, other) for other in bodies)]
    for kind, matches in (("name", [link for link in outermost if CUP_NAME.search(link)]),
                          ("shape", [link for link in outermost if _short_cylinder(tool.shapes(link))])):
        if len(matches) > 1:
            raise InferenceError(f"several links below '{tip}' look like a suction cup by their {kind} "
                                 f"({', '.join(sorted(matches))}): name it in the answers (suction.cup_link)")
        if matches:
            return matches[0], kind
    return None


def _face(tool: _Tool, cup: str, cup_pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(face centre, approach axis) in the tip frame."""
    shapes = tool.shapes(cup)
    if len(shapes) == 1 and shapes[0]["type"] == "cylinder":
        geometry = cup_pose @ _transform(shapes[0])
        centre, axis = geometry[:3, 3], geometry[:3, 2]
        half = shapes[0]["length"] / 2.0
        ends = (centre + half * axis, centre - half * axis)
        if np.linalg.norm(ends[1]) > np.linalg.norm(ends[0]):
            return ends[1], -axis
        return ends[0], axis
    return cup_pose[:3, 3], cup_pose[:3, 2]


def find_tool(model: dict[str, Any], tip: str, answers: dict[str, Any]) -> SuctionTool | None:
    """The suction tool below the arm's tip (the answers' `suction`, else inferred) in the core's model description,
    or None. Call it only when the arm has no gripper joints. Raises InferenceError naming the problem."""
    tool_model = _Tool(model)
    below = tool_model.fixed_below(tip)
    given = answers.get("suction", {})
    if "cup_link" in given:
        cup = given["cup_link"]
        if cup not in tool_model.links:
            raise InferenceError(f"answers suction.cup_link: no link '{cup}' in the robot")
        if cup not in below:
            raise InferenceError(f"answers suction.cup_link: '{cup}' is not fixed below the arm's tip '{tip}' "
                                 "(a suction cup has no moving joint between it and the arm)")
        found_by = "answers"
    else:
        inferred = _infer_cup(tool_model, below, tip)
        if inferred is None:
            if given:
                raise InferenceError(f"answers suction: no cup link found below the arm's tip '{tip}': give "
                                     "suction.cup_link")
            return None
        cup, found_by = inferred
    face, approach = _face(tool_model, cup, below[cup])
    tcp_source = "cup face"
    add_tcp_link = TCP_FRAME not in tool_model.links
    if not add_tcp_link:
        if TCP_FRAME not in below:
            raise InferenceError(f"link '{TCP_FRAME}' is not fixed below the arm's tip '{tip}': it cannot be the "
                                 "suction cup's TCP")
        face, approach, tcp_source = below[TCP_FRAME][:3, 3], below[TCP_FRAME][:3, 2], f"link '{TCP_FRAME}'"
        rotation = below[TCP_FRAME][:3, :3]
    else:
        rotation = _square_frame(approach, below[cup][:3, :3])
    return SuctionTool(cup_link=cup, parent_link=tip, tcp_xyz=[_clean(v) for v in face],
                       tcp_rpy=[_clean(v) for v in _rpy(rotation)], approach=[_clean(v) for v in approach],
                       found_by=found_by, tcp_source=tcp_source,
                       settings={**SUCTION_DEFAULTS, **{k: v for k, v in given.items() if k != "cup_link"}},
                       add_tcp_link=add_tcp_link)


def _square_frame(z: np.ndarray, cup_rotation: np.ndarray) -> np.ndarray:
    """A rotation whose z is `z` and whose x is the cup link's x (else y) made square to it."""
    z = z / np.linalg.norm(z)
    for reference in (cup_rotation[:, 0], cup_rotation[:, 1]):
        x = reference - (reference @ z) * z
        if np.linalg.norm(x) > 1e-6:
            x = x / np.linalg.norm(x)
            return np.column_stack([x, np.cross(z, x), z])
    raise AssertionError("the cup link's x and y axes are both along the approach")


def _clean(value: float) -> float:
    return round(float(value), 9) + 0.0


def with_tcp_link(urdf_text: str, tool: SuctionTool) -> str:
    """The URDF (the core's repaired one) with the link `tcp` fixed at the cup's face, unless it has one: a link
    and a joint added before `</robot>`, as the core adds a gripper's TCP."""
    if not tool.add_tcp_link:
        return urdf_text
    xyz = " ".join(repr(v) for v in tool.tcp_xyz)
    rpy = " ".join(repr(v) for v in tool.tcp_rpy)
    frame = (f'  <link name="{TCP_FRAME}"/>\n  <joint name="{TCP_FRAME}_joint" type="fixed">\n'
             f'    <parent link="{tool.parent_link}"/>\n    <child link="{TCP_FRAME}"/>\n'
             f'    <origin xyz="{xyz}" rpy="{rpy}"/>\n  </joint>\n')
    end = urdf_text.rindex("</robot>")
    return urdf_text[:end] + frame + urdf_text[end:]


def attach(plan: Plan, model: dict[str, Any], answers: dict[str, Any]) -> None:
    """Gives a plan without gripper joints its suction tool, group and end effector when the robot has one (the
    answers' `gripper: none` without `suction` says it has no tool). Raises InferenceError naming the problem."""
    if plan.gripper is not None or (answers.get("gripper") == "none" and "suction" not in answers):
        return
    tip = plan.arm.tip_link or next(j["child"] for j in model["joints"] if j["name"] == plan.arm.joints[-1])
    tool = find_tool(model, tip, answers)
    if tool is None:
        return
    names = answers.get("gripper") if isinstance(answers.get("gripper"), dict) else {}
    tool.group = names.get("group", tool.group)
    tool.controller = names.get("controller", tool.controller)
    if tool.group == plan.arm.name:
        raise InferenceError(f"answers gripper.group: '{tool.group}' is the arm group's name too")
    if tool.controller == plan.arm.controller:
        raise InferenceError(f"answers: the arm and the suction cup both use controller '{tool.controller}'")
    given = answers.get("end_effector", {})
    if given.get("parent_link", tip) != tip:
        raise InferenceError(f"answers end_effector.parent_link: a suction tool's end effector hangs on the arm's tip "
                             f"'{tip}', not '{given['parent_link']}'")
    plan.suction = tool
    plan.end_effector = {"name": given.get("name", "hand"), "parent_link": tip, "group": tool.group}


def grasping_data(plan: Plan) -> dict[str, Any]:
    """config/grasping.yaml of a suction tool: its group and end effector, the TCP at the cup's face, the approach,
    and the simulator's `suction` section (cup frame = the TCP)."""
    tool = plan.suction
    assert plan.end_effector is not None
    return {
        "group": tool.group,
        "end_effector": plan.end_effector["name"],
        "tcp": {"frame": TCP_FRAME, "parent_link": tool.parent_link, "xyz": tool.tcp_xyz, "rpy": tool.tcp_rpy,
                "source": tool.tcp_source},
        "approach_direction": tool.approach,
        "suction": {"cup_link": TCP_FRAME, **tool.settings, "controller": tool.controller, "arm_name": plan.arm.name},
    }


def grasping_yaml(plan: Plan) -> str:
    return ("# Generated by `rosrun sixdof_setup_assistant setup_assistant`: the suction tool,\n"
            f"# its cup `{plan.suction.cup_link}` {FOUND[plan.suction.found_by]} (docs/your_own_arm.md \"Suction "
            "tools\").\n# The TCP (the URDF link `tcp`) is at the centre of the cup's face, z along the approach, in\n"
            "# tcp.parent_link. suction: the simulator's cup (its face is the plane through cup_link's origin, +z out\n"
            "# of the cup); the vacuum is control_msgs/GripperCommand on <controller>/gripper_cmd (position > 0 on).\n"
            + yaml.safe_dump(grasping_data(plan), sort_keys=False, default_flow_style=None))


def readme_section(plan: Plan) -> str:
    """The README's section on the suction tool: what was inferred and how."""
    tool = plan.suction
    how = {"answers": "named in the answers file (suction.cup_link)",
           "name": "inferred: no moving joint below the arm's tip, and its name says cup/suction/vacuum",
           "shape": "inferred: no moving joint below the arm's tip, and its geometry is a short cylinder"}
    how = how[tool.found_by]
    xyz = ", ".join(f"{v:.4f}" for v in tool.tcp_xyz)
    rpy = ", ".join(f"{v:.4f}" for v in tool.tcp_rpy)
    settings = ", ".join(f"{k} {v:g}" for k, v in tool.settings.items())
    return f"""
## Suction tool (`config/grasping.yaml`)

- cup: link `{tool.cup_link}` ({how}); group `{tool.group}` (its links), end effector
  `{plan.end_effector['name']}` on `{tool.parent_link}`
- TCP: link `{TCP_FRAME}` at xyz ({xyz}) m, rpy ({rpy}) rad in `{tool.parent_link}` ({tool.tcp_source}); z along
  the approach; the simulator's cup frame
- vacuum: control_msgs/GripperCommand on `{tool.controller}/gripper_cmd` (position > 0 on, <= 0 off), served by
  the simulator; {settings}
"""
