"""config/sixdof.srdf of the designed arm, keeping the hand-written parts of the previous one."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from sixdof_description.formatting import HEADER, fmt
from sixdof_description.robot_design import ARM_JOINTS, GRIPPER_JOINTS, JOINT_LINKS, LINKS, Robot


def adjacent_pairs() -> list[tuple[str, str]]:
    """Links joined by a joint; a link without geometry (tcp) passes adjacency on to its parent."""
    pairs = []
    for parent, child in JOINT_LINKS.values():
        if child in LINKS and parent in LINKS:
            pairs.append((parent, child))
    return pairs


def preserved_srdf_elements(previous: str | None, generated_states: set) -> tuple[list, list]:
    """Hand-written group_states and non-Adjacent disabled pairs (added by the setup tool) of an older SRDF."""
    if not previous:
        return [], []
    root = ET.fromstring(previous)
    states = [e for e in root.findall("group_state") if (e.get("name"), e.get("group")) not in generated_states]
    pairs = [e for e in root.findall("disable_collisions") if e.get("reason") != "Adjacent"]
    return states, pairs


def render_srdf(robot: Robot, previous: str | None) -> str:
    d = robot.design
    generated = {(name, "arm") for name in robot.states} | {(name, "gripper") for name in d["gripper_states"]}
    kept_states, kept_pairs = preserved_srdf_elements(previous, generated)
    out = ['<?xml version="1.0"?>', f"<!-- {HEADER}", "     Hand-written group_states and non-Adjacent",
           "     disable_collisions entries are kept when it regenerates this file. -->",
           f'<robot name="{d["robot_name"]}">',
           '  <group name="arm">', '    <chain base_link="base_link" tip_link="link6"/>', "  </group>",
           '  <group name="gripper">']
    out += [f'    <joint name="{j}"/>' for j in GRIPPER_JOINTS]
    out.append("  </group>")
    for name, q in robot.states.items():
        out.append(f'  <group_state name="{name}" group="arm">')
        out += [f'    <joint name="{j}" value="{fmt(v)}"/>' for j, v in zip(ARM_JOINTS, q, strict=True)]
        out.append("  </group_state>")
    for name, value in d["gripper_states"].items():
        # The actuated finger only: the other mimics it (named states list no mimic joints, as MoveIt's).
        out.append(f'  <group_state name="{name}" group="gripper">')
        out.append(f'    <joint name="{GRIPPER_JOINTS[0]}" value="{fmt(value)}"/>')
        out.append("  </group_state>")
    for element in kept_states:
        ET.indent(element, space="  ", level=1)
        out.append("  " + _srdf_xml(element))
    out.append('  <end_effector name="hand" parent_link="link6" group="gripper"/>')
    out.append('  <virtual_joint name="virtual_joint" type="fixed" parent_frame="world" child_link="base_link"/>')
    for a, b in adjacent_pairs():
        out.append(f'  <disable_collisions link1="{a}" link2="{b}" reason="Adjacent"/>')
    for element in kept_pairs:
        element.tail = None
        out.append("  " + _srdf_xml(element))
    out.append("</robot>")
    return "\n".join(out) + "\n"


def _srdf_xml(element: ET.Element) -> str:
    """An element as one SRDF line, with empty elements closed as `/>` like every other line of the file (and
    like sixdof_setup_assistant writes them), so that either tool leaves the other's output unchanged."""
    return ET.tostring(element, encoding="unicode").strip().replace(" />", "/>")
