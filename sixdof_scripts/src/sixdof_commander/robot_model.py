"""The robot model the commander works with: joints, limits, groups, named states.

The model comes from move_group's `get_robot_model` service (`model_from_response`): move_group's C++ core
RobotModel is the project's only URDF/SRDF reader, so the commander agrees with the planner, the simulator and
rviz on joint order, limits (a continuous joint: `bounded` False, nominal limits -pi..pi) and groups, as
moveit_commander gets them from MoveIt's C++ RobotModel. Nothing here parses XML: scene_mirror and the perception
node ask move_group too (sixdof_commander.scene_node), and the unit tests that run without a move_group build its
get_robot_model response from the core's Python bindings (sixdof_scripts/test/core_model.py).

Only what the commander needs: which joints a group moves (in order), their limits, the group's tip and
end-effector links, the named states, fixed offsets between links, the gripper's grasping information (its TCP,
open and closed states, widths: the package's grasping.yaml as move_group read it) and, when asked for
(`query_robot_model(..., collision_geometry=True)`), the links' collision shapes as move_group has them (the
perception node's self filter): no Python code reads geometry from robot_description.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from shape_msgs.msg import SolidPrimitive

from .exceptions import SixdofCommanderError, UnknownGroupError
from .transforms import matrix_from_pose


@dataclass(frozen=True, eq=False)
class Joint:
    """One URDF joint (compared by identity). A continuous joint is unbounded (`bounded` False) with the
    nominal lower/upper -pi/pi, the core's convention (docs/design.md "One robot model")."""

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
    mimic_multiplier: float = 1.0
    mimic_offset: float = 0.0

    @property
    def bounded(self) -> bool:
        """False for continuous joints: no position limit applies (lower/upper are a nominal -pi..pi)."""
        return self.type != "continuous"

    @property
    def is_active(self) -> bool:
        """True for joints a planner moves: not fixed and not mimicking another joint."""
        return self.type not in ("fixed", "floating", "planar") and self.mimic is None


@dataclass(frozen=True)
class RobotDescription:
    """The URDF's kinematic tree."""

    name: str
    root_link: str
    joints: dict[str, Joint]  # in the model's order (breadth-first from the root link)
    links: frozenset[str]
    link_order: tuple[str, ...] = ()  # the links in the model's order (empty when read offline)
    # link -> its sixdof_msgs/RobotModelLinkGeometry (links without collision shapes have none); None when the
    # model was queried without collision geometry.
    collision: Mapping[str, Any] | None = None

    def collision_points(self, link: str) -> np.ndarray:
        """Points (N x 3, link frame) whose convex hull bounds the link's collision shapes (`geometry_points`);
        none for a link without collision geometry."""
        if self.collision is None:
            raise SixdofCommanderError(
                "the robot model carries no collision geometry: query it with collision_geometry=True"
            )
        if link not in self.links:
            raise SixdofCommanderError(f"link '{link}' is not in the URDF '{self.name}'")
        geometry = self.collision.get(link)
        return geometry_points(geometry) if geometry is not None else np.zeros((0, 3))

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
    expanded: ExpandedGroup | None = None  # set when the group comes from move_group's model


@dataclass(frozen=True)
class ExpandedGroup:
    """A group as the core model expands it (chains and subgroups included), in model order."""

    active_joints: tuple[str, ...]
    joints: tuple[str, ...]
    links: tuple[str, ...]


@dataclass(frozen=True)
class EndEffector:
    """An SRDF <end_effector>."""

    name: str
    parent_link: str
    group: str
    parent_group: str


@dataclass(frozen=True, eq=False)
class GripperModel:
    """A gripper's grasping information (sixdof_msgs/RobotModelGripper: the config package's grasping.yaml as
    move_group read it). The TCP and the directions are in parent_link's frame; states name actuated joints only."""

    group: str
    end_effector: str
    tcp_frame: str
    parent_link: str
    tcp: np.ndarray  # 4x4: z along the approach, y along the closing direction
    open_state: str
    open_positions: dict[str, float]
    closed_state: str
    closed_positions: dict[str, float]
    max_opening: float  # m between the pads when open
    closed_width: float
    finger_reach: float  # m the fingers reach beyond the TCP along the approach
    palm_depth: float  # m an object between the pads may reach back from the TCP (inf: no palm across them)
    pad_links: tuple[str, ...]
    closing_direction: np.ndarray  # unit
    approach_direction: np.ndarray  # unit
    suction_cup: str = ""  # a suction tool's cup frame (grasping.yaml `suction`); empty: a gripper with fingers
    vacuum_controller: str = ""  # the suction tool's vacuum: <vacuum_controller>/gripper_cmd
    max_payload: float = 0.0  # kg the suction cup holds


@dataclass(frozen=True)
class SemanticDescription:
    """The SRDF: groups, named states per group, end effectors; and the grippers' grasping information."""

    name: str
    groups: dict[str, GroupSpec]
    group_states: dict[str, dict[str, dict[str, float]]] = field(default_factory=dict)
    end_effectors: tuple[EndEffector, ...] = ()
    virtual_joint_parent: str | None = None
    grippers: tuple[GripperModel, ...] = ()


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


def _expanded_tip(srdf: SemanticDescription, name: str, links: list[str]) -> str:
    """A group's tip: its chain's tip, else its first subgroup's tip that has one, else its last link."""
    spec = srdf.groups[name]
    if spec.chains:
        return spec.chains[-1][1]
    for subgroup in spec.subgroups:
        sub = srdf.groups.get(subgroup)
        if sub is not None and sub.expanded is not None:
            tip = _expanded_tip(srdf, subgroup, list(sub.expanded.links))
            if tip:
                return tip
    return links[-1] if links else ""


def _box_corners(half: np.ndarray) -> np.ndarray:
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    return signs * half


def primitive_points(primitive: Any) -> np.ndarray:
    """The 8 corners (its own frame) of the box around a shape_msgs/SolidPrimitive BOX, SPHERE or CYLINDER (along
    z); SixdofCommanderError naming the type or dimensions it cannot bound."""
    dims = list(primitive.dimensions)
    expected = {SolidPrimitive.BOX: 3, SolidPrimitive.SPHERE: 1, SolidPrimitive.CYLINDER: 2}
    if primitive.type not in expected:
        raise SixdofCommanderError(f"collision primitive type {primitive.type} is not a box, sphere or cylinder")
    if len(dims) != expected[primitive.type] or not all(math.isfinite(v) and v > 0.0 for v in dims):
        raise SixdofCommanderError(f"collision primitive type {primitive.type} has bad dimensions {dims}")
    if primitive.type == SolidPrimitive.BOX:
        half = np.array(dims) / 2.0
    elif primitive.type == SolidPrimitive.SPHERE:
        half = np.full(3, dims[0])
    else:  # CYLINDER: [height, radius]
        half = np.array([dims[1], dims[1], dims[0] / 2.0])
    return _box_corners(half)


def geometry_points(geometry: Any) -> np.ndarray:
    """Points (N x 3, link frame) whose convex hull bounds a sixdof_msgs/RobotModelLinkGeometry's shapes: the
    corners of the boxes around its primitives and its meshes' vertices, each placed at its pose."""
    primitives = zip(geometry.primitives, geometry.primitive_poses, strict=True)
    placed = [(primitive_points(primitive), pose) for primitive, pose in primitives]
    for mesh, pose in zip(geometry.meshes, geometry.mesh_poses, strict=True):
        placed.append((np.array([[v.x, v.y, v.z] for v in mesh.vertices], dtype=float).reshape(-1, 3), pose))
    points = []
    for local, pose in placed:
        frame = matrix_from_pose(pose)
        points.append(local @ frame[:3, :3].T + frame[:3, 3])
    return np.vstack(points) if points else np.zeros((0, 3))


def _state(msg: Any) -> dict[str, float]:
    return dict(zip(msg.joint_names, msg.positions, strict=True))


def _vector(msg: Any) -> np.ndarray:
    return np.array([msg.x, msg.y, msg.z], dtype=float)


def gripper_from_msg(msg: Any) -> GripperModel:
    """The GripperModel of a sixdof_msgs/RobotModelGripper."""
    return GripperModel(
        group=msg.group,
        end_effector=msg.end_effector,
        tcp_frame=msg.tcp_frame,
        parent_link=msg.parent_link,
        tcp=matrix_from_pose(msg.tcp),
        open_state=msg.open.name,
        open_positions=_state(msg.open),
        closed_state=msg.closed.name,
        closed_positions=_state(msg.closed),
        max_opening=msg.max_opening,
        closed_width=msg.closed_width,
        finger_reach=msg.finger_reach,
        palm_depth=msg.palm_depth,
        pad_links=tuple(msg.pad_links),
        closing_direction=_vector(msg.closing_direction),
        approach_direction=_vector(msg.approach_direction),
        suction_cup=msg.suction_cup,
        vacuum_controller=msg.vacuum_controller,
        max_payload=msg.max_payload,
    )


def model_from_response(response: object, collision: bool = False) -> tuple[RobotDescription, SemanticDescription]:
    """The robot model of a sixdof_msgs/GetRobotModel response (move_group's get_robot_model); its collision
    geometry when the request included it (`collision` is None otherwise)."""
    joints = {}
    for j in response.joints:
        joints[j.name] = Joint(
            name=j.name,
            type=j.type,
            parent=j.parent_link,
            child=j.child_link,
            origin=matrix_from_pose(j.origin),
            lower=j.min_position,
            upper=j.max_position,
            effort=j.max_effort,
            mimic=j.mimic_joint or None,
            axis=(j.axis.x, j.axis.y, j.axis.z),
            velocity=j.max_velocity if j.max_velocity > 0.0 else math.inf,
            mimic_multiplier=j.mimic_multiplier,
            mimic_offset=j.mimic_offset,
        )
    urdf = RobotDescription(
        name=response.robot_name,
        root_link=response.root_link,
        joints=joints,
        links=frozenset(response.link_names),
        link_order=tuple(response.link_names),
        collision={g.link_name: g for g in response.link_geometries} if collision else None,
    )
    groups = {
        g.name: GroupSpec(
            name=g.name,
            chains=((g.chain_base_link, g.chain_tip_link),) if g.chain_tip_link else (),
            joints=tuple(g.joints),
            links=tuple(g.links),
            subgroups=tuple(g.subgroups),
            expanded=ExpandedGroup(
                active_joints=tuple(g.active_joints), joints=tuple(g.joints), links=tuple(g.links)
            ),
        )
        for g in response.groups
    }
    states: dict[str, dict[str, dict[str, float]]] = {}
    for state in response.group_states:
        states.setdefault(state.group, {})[state.name] = dict(zip(state.joint_names, state.positions, strict=True))
    srdf = SemanticDescription(
        name=response.robot_name,
        groups=groups,
        group_states=states,
        end_effectors=tuple(
            EndEffector(name=e.name, parent_link=e.parent_link, group=e.group, parent_group=e.parent_group)
            for e in response.end_effectors
        ),
        virtual_joint_parent=response.planning_frame if response.planning_frame != response.root_link else None,
        grippers=tuple(gripper_from_msg(g) for g in response.grippers),
    )
    return urdf, srdf


def resolve_group(urdf: RobotDescription, srdf: SemanticDescription, name: str) -> Group:
    """The SRDF group `name` with its active joints in order, its links, tip and end-effector link."""
    if name not in srdf.groups:
        raise UnknownGroupError(f"the SRDF has no group '{name}'; groups: {sorted(srdf.groups)}")
    expanded = srdf.groups[name].expanded
    if expanded is None:
        raise SixdofCommanderError(
            f"group '{name}' is not expanded: the model must come from move_group's get_robot_model"
        )
    # move_group's model: its expansion and order.
    joints = [urdf.joints[joint] for joint in expanded.joints]
    links = list(expanded.links)
    tip = _expanded_tip(srdf, name, links)
    active = [urdf.joints[joint] for joint in expanded.active_joints]
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
