"""The robot's URDF and SRDF, parsed with xml.etree: joints, limits, groups, named states.

Only what the commander needs: which joints a group moves (in order), their limits, the group's tip and
end-effector links, the named states, and fixed offsets between links (link6 -> tcp).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

from .exceptions import SixdofCommanderError, UnknownGroupError
from .transforms import homogeneous, matrix_from_rpy


@dataclass(frozen=True, eq=False)
class Joint:
    """One URDF joint (compared by identity). lower/upper are -inf/inf for continuous joints."""

    name: str
    type: str
    parent: str
    child: str
    origin: np.ndarray  # 4x4 transform parent -> joint frame
    lower: float
    upper: float
    effort: float
    mimic: str | None
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0)
    velocity: float = math.inf  # the URDF's velocity limit (inf when absent)

    @property
    def is_active(self) -> bool:
        """True for joints a planner moves: not fixed and not mimicking another joint."""
        return self.type not in ("fixed", "floating", "planar") and self.mimic is None


@dataclass(frozen=True)
class RobotDescription:
    """The URDF's kinematic tree."""

    name: str
    root_link: str
    joints: dict[str, Joint]
    links: frozenset[str]

    def parent_joint(self, link: str) -> Joint | None:
        """The joint whose child is `link`, or None for the root."""
        for joint in self.joints.values():
            if joint.child == link:
                return joint
        return None

    def chain(self, base_link: str, tip_link: str) -> list[Joint]:
        """Joints from base_link down to tip_link, in order (all types)."""
        for link in (base_link, tip_link):
            if link not in self.links:
                raise SixdofCommanderError(f"link '{link}' is not in the URDF '{self.name}'")
        joints = []
        link = tip_link
        while link != base_link:
            joint = self.parent_joint(link)
            if joint is None:
                raise SixdofCommanderError(f"link '{tip_link}' is not below link '{base_link}' in the URDF")
            joints.append(joint)
            link = joint.parent
        return list(reversed(joints))

    def fixed_transform(self, from_link: str, to_link: str) -> np.ndarray:
        """4x4 transform of to_link in from_link, when only fixed joints separate them."""
        transform = np.eye(4)
        for joint in self.chain(from_link, to_link):
            if joint.type != "fixed":
                raise SixdofCommanderError(
                    f"links '{from_link}' and '{to_link}' are separated by the moving joint '{joint.name}'"
                )
            transform = transform @ joint.origin
        return transform

    def chain_transform(self, from_link: str, to_link: str) -> np.ndarray:
        """4x4 transform from from_link to the frame of the last joint above to_link, all joints at zero."""
        transform = np.eye(4)
        for joint in self.chain(from_link, to_link):
            transform = transform @ joint.origin
        return transform

    def descendant_links(self, link: str) -> list[str]:
        """link and every link below it in the tree."""
        found = [link]
        for joint in self.joints.values():
            if joint.parent == link:
                found.extend(self.descendant_links(joint.child))
        return found


@dataclass(frozen=True)
class GroupSpec:
    """An SRDF <group> as written: chains, joints, links and subgroups."""

    name: str
    chains: tuple[tuple[str, str], ...] = ()
    joints: tuple[str, ...] = ()
    links: tuple[str, ...] = ()
    subgroups: tuple[str, ...] = ()


@dataclass(frozen=True)
class EndEffector:
    """An SRDF <end_effector>."""

    name: str
    parent_link: str
    group: str
    parent_group: str


@dataclass(frozen=True)
class SemanticDescription:
    """The SRDF: groups, named states per group, end effectors."""

    name: str
    groups: dict[str, GroupSpec]
    group_states: dict[str, dict[str, dict[str, float]]] = field(default_factory=dict)
    end_effectors: tuple[EndEffector, ...] = ()
    virtual_joint_parent: str | None = None


@dataclass(frozen=True)
class Group:
    """A planning group resolved against the URDF."""

    name: str
    joints: tuple[Joint, ...]  # active joints, in order
    all_joints: tuple[Joint, ...]  # every joint of the group, fixed and mimic ones included
    links: tuple[str, ...]
    tip_link: str
    end_effector_link: str
    end_effector_group: str | None
    named_states: dict[str, dict[str, float]]

    @property
    def joint_names(self) -> list[str]:
        """Names of the group's active joints, in order."""
        return [joint.name for joint in self.joints]


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
        mimic = element.find("mimic")
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
        )
    children = {joint.child for joint in joints.values()}
    roots = sorted(links - children)
    if len(roots) != 1:
        raise SixdofCommanderError(f"the URDF must have exactly one root link, found {roots}")
    return RobotDescription(name=root.get("name", ""), root_link=roots[0], joints=joints, links=links)


def parse_srdf(text: str) -> SemanticDescription:
    """Parse an SRDF document."""
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


def resolve_group(urdf: RobotDescription, srdf: SemanticDescription, name: str) -> Group:
    """The SRDF group `name` with its active joints in order, its links, tip and end-effector link."""
    joints, links, tip = _group_joints_and_links(urdf, srdf, name, frozenset())
    active = []
    for joint in joints:
        if joint.is_active and joint not in active:
            active.append(joint)
    # MoveIt's rule: the group's end effector is one whose parent link belongs to the group.
    eef_link, eef_group = tip, None
    for eef in srdf.end_effectors:
        if eef.parent_group == name or (not eef.parent_group and eef.parent_link in links and eef.group != name):
            eef_link, eef_group = eef.parent_link, eef.group
            break
    states = srdf.group_states.get(name, {})
    names = {joint.name for joint in active} | {joint.name for joint in joints}
    for state, values in states.items():
        unknown = sorted(set(values) - names)
        if unknown:
            raise SixdofCommanderError(
                f"SRDF state '{state}' of group '{name}' names joints {unknown} not in the group"
            )
    return Group(
        name=name,
        joints=tuple(active),
        all_joints=tuple(dict.fromkeys(joints)),
        links=tuple(dict.fromkeys(links)),
        tip_link=tip,
        end_effector_link=eef_link,
        end_effector_group=eef_group,
        named_states={state: dict(values) for state, values in states.items()},
    )


def group_links_with_descendants(urdf: RobotDescription, group: Group) -> list[str]:
    """The group's links plus everything attached below them (e.g. the fingers' children)."""
    links: list[str] = []
    for link in group.links:
        for found in urdf.descendant_links(link):
            if found not in links:
                links.append(found)
    return links
