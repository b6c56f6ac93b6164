"""Which planning-scene changes make move_group's scene match a set of objects: the simulator's (sixdof_bringup's
scene_mirror) or the tracked detections (sixdof_perception's perception_node). No ROS communication.

The mirror reconciles two snapshots instead of replaying events, so a missed message or a failed service
call is repaired on the next cycle, and changes made by other clients (sixdof_commander's ArmDriver attaches
and detaches the object it grasps) are respected rather than fought over.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from geometry_msgs.msg import Pose
from moveit_msgs.msg import AttachedCollisionObject, CollisionObject
from shape_msgs.msg import Mesh, SolidPrimitive

from sixdof_msgs.msg import SimObject

from .transforms import rotation_angle


@dataclass(frozen=True)
class SimObjectState:
    """One simulator object as published on sixdof_sim/object_states."""

    name: str
    pose: Pose
    attached_to: str  # link holding it through the grasp fix; empty when free


@dataclass(frozen=True)
class SceneSnapshot:
    """What move_group's scene holds: world object poses and attached objects' links, by id."""

    world: Mapping[str, Pose]
    attached: Mapping[str, str]


@dataclass
class Updates:
    """One cycle's changes: world-object operations and attach/detach requests."""

    world_objects: list[CollisionObject] = field(default_factory=list)
    attached_objects: list[AttachedCollisionObject] = field(default_factory=list)

    def empty(self) -> bool:
        return not self.world_objects and not self.attached_objects


def position_distance(a: Pose, b: Pose) -> float:
    """Euclidean distance between the positions of two poses (m)."""
    return math.dist((a.position.x, a.position.y, a.position.z), (b.position.x, b.position.y, b.position.z))


def orientation_angle(a: Pose, b: Pose) -> float:
    """Angle (rad) of the rotation between the orientations of two poses."""
    qa, qb = a.orientation, b.orientation
    return rotation_angle((qa.x, qa.y, qa.z, qa.w), (qb.x, qb.y, qb.z, qb.w))


def _check_threshold(value: float, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value < 0.0:
        raise ValueError(f"{what} must be a finite number >= 0, got {value!r}")
    return float(value)


class SceneMirror:
    """Decides the planning-scene updates that mirror the simulator's objects.

    shapes: per object name, a CollisionObject template holding the object's shapes (primitives or meshes
    with their poses relative to the object frame); objects without a template are not mirrored (visual
    markers, objects to ignore). Per cycle, for each mirrored object:
      - free in the simulator and unknown to the scene: ADD at the simulator's pose;
      - free and in the scene's world: MOVE when position or orientation changed above the thresholds;
      - held by the grasp fix (attached_to a link) but not attached in the scene: attach it to that link
        with its shapes at the simulator's pose, touch_links(link) allowed to touch it;
      - free in the simulator but attached in the scene: detach it (the next cycle MOVEs it where it fell).
    Attaching and detaching wait `grace` seconds after the simulator changed, so that a script managing
    its own grasps (ArmDriver) does it first; the mirror only repairs what nobody else did.
    Objects the mirror added that disappear from the simulator are removed from the scene.
    An object someone else removed from the scene (remove_world_object, clear) while the simulator still has it
    stays out, as a MoveIt client expects of its removal: the mirror leaves it alone until it disappears from
    the simulator (a new object of that name is mirrored again).
    Static objects (names in `static`: tables, walls) are mirrored support_clearance lower: the robot stands
    on the table, and the planning-scene message has no allowed-collision entries to let base_link touch it.
    """

    def __init__(
        self,
        shapes: Mapping[str, CollisionObject],
        planning_frame: str,
        touch_links: Callable[[str], Sequence[str]],
        position_threshold: float = 0.001,
        angle_threshold: float = 0.01,
        grace: float = 0.5,
        support_clearance: float = 0.002,
    ) -> None:
        if not planning_frame:
            raise ValueError("planning_frame must be a non-empty frame name")
        self.shapes = dict(shapes)
        self.planning_frame = planning_frame
        self.touch_links = touch_links
        self.position_threshold = _check_threshold(position_threshold, "position_threshold")
        self.angle_threshold = _check_threshold(angle_threshold, "angle_threshold")
        self.grace = _check_threshold(grace, "grace")
        self.support_clearance = _check_threshold(support_clearance, "support_clearance")
        self.static: set[str] = set()
        self.managed: set[str] = set()
        # Objects seen in the scene (world or attached) while the simulator has them; one of them missing from the
        # scene later was removed by a client, and goes into `removed` (not mirrored while the simulator has it).
        self.seen: set[str] = set()
        self.removed: set[str] = set()
        self._mismatch_since: dict[str, float] = {}

    def _scene_pose(self, name: str, pose: Pose) -> Pose:
        if name not in self.static:
            return pose
        lowered = copy.deepcopy(pose)
        lowered.position.z -= self.support_clearance
        return lowered

    def _placed(self, name: str, pose: Pose, operation: int) -> CollisionObject:
        template = self.shapes[name]
        obj = CollisionObject()
        obj.header.frame_id = self.planning_frame
        obj.id = name
        obj.pose = self._scene_pose(name, pose)
        obj.operation = operation
        if operation == CollisionObject.ADD:
            obj.primitives = list(template.primitives)
            obj.primitive_poses = list(template.primitive_poses)
            obj.meshes = list(template.meshes)
            obj.mesh_poses = list(template.mesh_poses)
        return obj

    def _grace_over(self, name: str, now: float) -> bool:
        since = self._mismatch_since.setdefault(name, now)
        return now - since >= self.grace

    def update(self, objects: Sequence[SimObjectState], scene: SceneSnapshot, now: float) -> Updates:
        """The changes for this cycle; now is a monotonic time in seconds (for the grace period)."""
        updates = Updates()
        present = set()
        for state in objects:
            present.add(state.name)
            if state.name not in self.shapes or self._removed_by_client(state.name, scene):
                continue
            held = bool(state.attached_to)
            attached_link = scene.attached.get(state.name)
            if held != (attached_link is not None):
                if self._grace_over(state.name, now):
                    self._mismatch_since.pop(state.name)
                    updates.attached_objects.append(self._attach_change(state))
                    self.managed.add(state.name)
                continue
            self._mismatch_since.pop(state.name, None)
            if held:
                continue
            known = scene.world.get(state.name)
            if known is None:
                updates.world_objects.append(self._placed(state.name, state.pose, CollisionObject.ADD))
                self.managed.add(state.name)
            elif (
                position_distance(known, self._scene_pose(state.name, state.pose)) > self.position_threshold
                or orientation_angle(known, state.pose) > self.angle_threshold
            ):
                updates.world_objects.append(self._placed(state.name, state.pose, CollisionObject.MOVE))
                self.managed.add(state.name)
        for name in sorted(self.managed - present):
            if name in scene.attached:
                detach = AttachedCollisionObject()
                detach.object.id = name
                detach.object.operation = CollisionObject.REMOVE
                updates.attached_objects.append(detach)
            elif name in scene.world:
                removal = CollisionObject(id=name, operation=CollisionObject.REMOVE)
                removal.header.frame_id = self.planning_frame
                updates.world_objects.append(removal)
            else:
                self.managed.discard(name)
                self._mismatch_since.pop(name, None)
        self.seen &= present
        self.removed &= present
        return updates

    def _removed_by_client(self, name: str, scene: SceneSnapshot) -> bool:
        """Whether `name` (an object of the simulator) is one a client removed from the scene; tracks `seen`."""
        if name in self.removed:
            return True
        if name in scene.world or name in scene.attached:
            self.seen.add(name)
            return False
        if name not in self.seen:
            return False
        self.seen.discard(name)
        self.removed.add(name)
        self.managed.discard(name)
        self._mismatch_since.pop(name, None)
        return True

    def _attach_change(self, state: SimObjectState) -> AttachedCollisionObject:
        attached = AttachedCollisionObject()
        if state.attached_to:
            attached.link_name = state.attached_to
            attached.object = self._placed(state.name, state.pose, CollisionObject.ADD)
            attached.touch_links = list(self.touch_links(state.attached_to))
        else:
            attached.object.id = state.name
            attached.object.operation = CollisionObject.REMOVE
        return attached


def template_from_sim_object(obj: SimObject, load_mesh: Callable[[str, Sequence[float]], Mesh]) -> CollisionObject:
    """A shape template (no pose, no operation) from the simulator's object description: its primitive,
    or its mesh (load_mesh(resource, scale)) when mesh_resource is set."""
    template = CollisionObject()
    template.id = obj.name
    identity = Pose()
    identity.orientation.w = 1.0
    if obj.mesh_resource:
        scale = [obj.mesh_scale.x, obj.mesh_scale.y, obj.mesh_scale.z]
        template.meshes.append(load_mesh(obj.mesh_resource, scale))
        template.mesh_poses.append(identity)
        return template
    expected = {SolidPrimitive.BOX: 3, SolidPrimitive.SPHERE: 1, SolidPrimitive.CYLINDER: 2}
    if obj.shape.type not in expected:
        raise ValueError(f"object '{obj.name}': unsupported shape type {obj.shape.type}")
    if len(obj.shape.dimensions) != expected[obj.shape.type] or not all(d > 0.0 for d in obj.shape.dimensions):
        raise ValueError(f"object '{obj.name}': bad shape dimensions {list(obj.shape.dimensions)}")
    template.primitives.append(SolidPrimitive(type=obj.shape.type, dimensions=list(obj.shape.dimensions)))
    template.primitive_poses.append(identity)
    return template
