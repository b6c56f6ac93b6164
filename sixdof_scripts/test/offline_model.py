"""Test-only URDF/SRDF reader: the models of the pure-logic unit tests, which run without a move_group.

The commander itself never parses the robot description: it gets the model from move_group's get_robot_model
(sixdof_commander.robot_model.model_from_response), the core RobotModel being the only URDF/SRDF reader. These
tests need a model without a ROS master, so this module builds one from the fixture files by the same conventions
(continuous joints unbounded with nominal -pi..pi; groups expanded from chains, joints, links and subgroups),
with the groups in SRDF declaration order rather than the core's breadth-first model order.
"""

from __future__ import annotations

import dataclasses
import math
import xml.etree.ElementTree as ET

from sixdof_commander.exceptions import SixdofCommanderError, UnknownGroupError
from sixdof_commander.robot_model import (
    EndEffector,
    ExpandedGroup,
    GroupSpec,
    Joint,
    RobotDescription,
    SemanticDescription,
)
from sixdof_commander.transforms import homogeneous, matrix_from_rpy


def _parse_xml(text: str, what: str) -> ET.Element:
    try:
        return ET.fromstring(text)
    except ET.ParseError as err:
        raise SixdofCommanderError(f"cannot parse the {what}: {err}") from err


def _floats(text: str | None, count: int, what: str) -> list[float]:
    """count numbers from an attribute; None (attribute absent) means zeros, as URDF origins default."""
    try:
        values = [float(v) for v in (text if text is not None else " ".join(["0"] * count)).split()]
    except ValueError:
        raise SixdofCommanderError(f"{what} must be {count} numbers, got '{text}'") from None
    if len(values) != count:
        raise SixdofCommanderError(f"{what} must be {count} numbers, got '{text}'")
    return values


def _required(element: ET.Element, attribute: str, what: str) -> str:
    value = element.get(attribute)
    if value is None:
        raise SixdofCommanderError(f"{what} has no '{attribute}' attribute")
    return value


def parse_urdf(text: str) -> RobotDescription:
    """Parse a URDF document."""
    root = _parse_xml(text, "URDF")
    if root.tag != "robot":
        raise SixdofCommanderError(f"the URDF's root element is <{root.tag}>, expected <robot>")
    links = frozenset(_required(link, "name", "a URDF <link>") for link in root.findall("link"))
    joints = {}
    for element in root.findall("joint"):
        name = _required(element, "name", "a URDF <joint>")
        what = f"URDF joint '{name}'"
        joint_type = _required(element, "type", what)
        origin = element.find("origin")
        xyz = _floats(origin.get("xyz") if origin is not None else None, 3, f"{what} origin xyz")
        rpy = _floats(origin.get("rpy") if origin is not None else None, 3, f"{what} origin rpy")
        limit = element.find("limit")
        lower, upper, effort, velocity = -math.inf, math.inf, 0.0, math.inf
        if limit is not None:
            effort = _floats(limit.get("effort"), 1, f"{what} limit effort")[0]
            if limit.get("velocity") is not None:
                velocity = _floats(limit.get("velocity"), 1, f"{what} limit velocity")[0]
            if joint_type in ("revolute", "prismatic"):
                lower = _floats(limit.get("lower"), 1, f"{what} limit lower")[0]
                upper = _floats(limit.get("upper"), 1, f"{what} limit upper")[0]
        if joint_type == "continuous":
            lower, upper = -math.pi, math.pi
        mimic = element.find("mimic")
        mimic_values = (
            [_floats(mimic.get(key, default), 1, f"{what} <mimic> {key}")[0] for key, default in
             (("multiplier", "1"), ("offset", "0"))]
            if mimic is not None
            else [1.0, 0.0]
        )
        axis = element.find("axis")
        joints[name] = Joint(
            name=name,
            type=joint_type,
            parent=_required(element.find("parent"), "link", f"{what} <parent>"),
            child=_required(element.find("child"), "link", f"{what} <child>"),
            origin=homogeneous(xyz, matrix_from_rpy(*rpy)),
            lower=lower,
            upper=upper,
            effort=effort,
            mimic=_required(mimic, "joint", f"{what} <mimic>") if mimic is not None else None,
            axis=tuple(_floats(axis.get("xyz") if axis is not None else "1 0 0", 3, f"{what} axis")),
            velocity=velocity,
            mimic_multiplier=mimic_values[0],
            mimic_offset=mimic_values[1],
        )
    children = {joint.child for joint in joints.values()}
    roots = sorted(links - children)
    if len(roots) != 1:
        raise SixdofCommanderError(f"the URDF must have exactly one root link, found {roots}")
    return RobotDescription(name=root.get("name", ""), root_link=roots[0], joints=joints, links=links)


def _parse_srdf(text: str) -> SemanticDescription:
    """The SRDF as written (groups not yet expanded)."""
    root = _parse_xml(text, "SRDF")
    if root.tag != "robot":
        raise SixdofCommanderError(f"the SRDF's root element is <{root.tag}>, expected <robot>")
    groups = {}
    for element in root.findall("group"):
        name = _required(element, "name", "an SRDF <group>")
        what = f"SRDF group '{name}'"
        groups[name] = GroupSpec(
            name=name,
            chains=tuple(
                (_required(c, "base_link", f"{what} <chain>"), _required(c, "tip_link", f"{what} <chain>"))
                for c in element.findall("chain")
            ),
            joints=tuple(_required(j, "name", f"{what} <joint>") for j in element.findall("joint")),
            links=tuple(_required(lk, "name", f"{what} <link>") for lk in element.findall("link")),
            subgroups=tuple(_required(g, "name", f"{what} <group>") for g in element.findall("group")),
        )
    states: dict[str, dict[str, dict[str, float]]] = {}
    for element in root.findall("group_state"):
        name = _required(element, "name", "an SRDF <group_state>")
        group = _required(element, "group", f"SRDF group_state '{name}'")
        values = {}
        for joint in element.findall("joint"):
            joint_name = _required(joint, "name", f"SRDF group_state '{name}' <joint>")
            what = f"SRDF group_state '{name}' joint '{joint_name}' value"
            values[joint_name] = _floats(_required(joint, "value", what), 1, what)[0]
        states.setdefault(group, {})[name] = values
    end_effectors = tuple(
        EndEffector(
            name=_required(e, "name", "an SRDF <end_effector>"),
            parent_link=_required(e, "parent_link", "an SRDF <end_effector>"),
            group=_required(e, "group", "an SRDF <end_effector>"),
            parent_group=e.get("parent_group", ""),
        )
        for e in root.findall("end_effector")
    )
    virtual = root.find("virtual_joint")
    return SemanticDescription(
        name=root.get("name", ""),
        groups=groups,
        group_states=states,
        end_effectors=end_effectors,
        virtual_joint_parent=virtual.get("parent_frame") if virtual is not None else None,
    )


def _group_joints_and_links(
    urdf: RobotDescription, srdf: SemanticDescription, name: str, seen: frozenset[str]
) -> tuple[list[Joint], list[str], str]:
    if name not in srdf.groups:
        raise UnknownGroupError(f"the SRDF has no group '{name}'; groups: {sorted(srdf.groups)}")
    if name in seen:
        raise SixdofCommanderError(f"SRDF group '{name}' contains itself through its subgroups")
    spec = srdf.groups[name]
    joints: list[Joint] = []
    links: list[str] = []
    tip = ""
    for base, tip_link in spec.chains:
        chain = urdf.chain(base, tip_link)
        joints.extend(chain)
        links.extend(joint.child for joint in chain)
        tip = tip_link
    for joint_name in spec.joints:
        if joint_name not in urdf.joints:
            raise SixdofCommanderError(f"SRDF group '{name}' names joint '{joint_name}', which is not in the URDF")
        joints.append(urdf.joints[joint_name])
        links.append(urdf.joints[joint_name].child)
    for link in spec.links:
        joint = urdf.parent_joint(link)
        if link not in urdf.links:
            raise SixdofCommanderError(f"SRDF group '{name}' names link '{link}', which is not in the URDF")
        if joint is not None:
            joints.append(joint)
        links.append(link)
    for subgroup in spec.subgroups:
        sub_joints, sub_links, sub_tip = _group_joints_and_links(urdf, srdf, subgroup, seen | {name})
        joints.extend(sub_joints)
        links.extend(sub_links)
        tip = tip or sub_tip
    return joints, links, tip or (links[-1] if links else "")


def parse_srdf(text: str, urdf: RobotDescription) -> SemanticDescription:
    """An SRDF document with its groups expanded against `urdf` (as move_group's model has them)."""
    srdf = _parse_srdf(text)
    groups = {}
    for name, spec in srdf.groups.items():
        joints, links, _ = _group_joints_and_links(urdf, srdf, name, frozenset())
        active = [joint.name for joint in dict.fromkeys(joints) if joint.is_active]
        groups[name] = dataclasses.replace(
            spec,
            expanded=ExpandedGroup(
                active_joints=tuple(active),
                joints=tuple(joint.name for joint in dict.fromkeys(joints)),
                links=tuple(dict.fromkeys(links)),
            ),
        )
    return dataclasses.replace(srdf, groups=groups)
