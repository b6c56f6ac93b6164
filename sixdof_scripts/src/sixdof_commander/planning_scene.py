"""PlanningScene: add/remove/attach collision objects of the move_group node's planning scene."""

from __future__ import annotations

from collections.abc import Sequence

import rospkg
import rospy
from geometry_msgs.msg import Pose
from shape_msgs.msg import SolidPrimitive

from sixdof_msgs.msg import AttachedCollisionObject, CollisionObject, MoveItErrorCodes
from sixdof_msgs.msg import PlanningScene as SceneMsg
from sixdof_msgs.srv import ApplyPlanningScene, GetPlanningScene

from ._ros import ServerWaiter, load_robot_model, require_node, resolve
from .exceptions import SixdofCommanderError
from .goals import check_positive, pose_stamped_from_target
from .mesh import load_stl
from .robot_model import RobotDescription, SemanticDescription, group_links_with_descendants, resolve_group


def default_touch_links(urdf: RobotDescription, srdf: SemanticDescription, link: str) -> list[str]:
    """Links an object attached to `link` may touch: the link, links fixed to it (palm, tcp) and the
    links of the end effectors mounted on it (the fingers), as MoveIt's commander chooses them."""
    if link not in urdf.links:
        raise SixdofCommanderError(f"link '{link}' is not a link of the robot")
    links = [link]
    for joint in urdf.joints.values():
        if joint.parent in links and joint.type == "fixed" and joint.child not in links:
            links.append(joint.child)
    for eef in srdf.end_effectors:
        if eef.parent_link == link:
            for found in group_links_with_descendants(urdf, resolve_group(urdf, srdf, eef.group)):
                if found not in links:
                    links.append(found)
    return links


def _check_name(name: object, what: str = "object name") -> str:
    if not isinstance(name, str) or not name:
        raise SixdofCommanderError(f"{what} must be a non-empty string, got {name!r}")
    return name


def _check_size(size: Sequence[float], what: str) -> list[float]:
    if isinstance(size, str) or not isinstance(size, Sequence) or len(size) != 3:
        raise SixdofCommanderError(f"{what} must be 3 numbers (x, y, z), got {size!r}")
    return [check_positive(v, f"{what}[{i}]") for i, v in enumerate(size)]


def _identity() -> Pose:
    pose = Pose()
    pose.orientation.w = 1.0
    return pose


def collision_object(name: str, pose: object, planning_frame: str) -> CollisionObject:
    """An ADD CollisionObject without shapes, at pose (empty frame: the planning frame)."""
    stamped = pose_stamped_from_target(pose, planning_frame, f"pose of '{name}'")
    obj = CollisionObject()
    obj.header = stamped.header
    obj.id = _check_name(name)
    obj.pose = stamped.pose
    obj.operation = CollisionObject.ADD
    return obj


def primitive_object(
    name: str, pose: object, shape_type: int, dimensions: Sequence[float], planning_frame: str
) -> CollisionObject:
    """An ADD CollisionObject of one solid primitive centred at pose."""
    obj = collision_object(name, pose, planning_frame)
    obj.primitives.append(SolidPrimitive(type=shape_type, dimensions=list(dimensions)))
    obj.primitive_poses.append(_identity())
    return obj


def removal(name: str, planning_frame: str) -> CollisionObject:
    """A REMOVE CollisionObject."""
    obj = CollisionObject()
    obj.id = _check_name(name)
    obj.header.frame_id = planning_frame
    obj.operation = CollisionObject.REMOVE
    return obj


def attach_request(name: str, link: str, touch_links: Sequence[str]) -> AttachedCollisionObject:
    """Attach the existing world object `name` to `link` (no shapes: the planner moves it from the world)."""
    attached = AttachedCollisionObject()
    attached.link_name = link
    attached.object.id = _check_name(name)
    attached.object.header.frame_id = link
    attached.object.operation = CollisionObject.ADD
    attached.touch_links = list(touch_links)
    return attached


def detach_request(name: str) -> AttachedCollisionObject:
    """Detach `name` (every attached object when empty) back into the world."""
    attached = AttachedCollisionObject()
    attached.object.id = name
    attached.object.operation = CollisionObject.REMOVE
    return attached


def scene_diff(
    world_objects: Sequence[CollisionObject] = (), attached: Sequence[AttachedCollisionObject] = ()
) -> SceneMsg:
    """A planning-scene diff carrying world-object and attached-object changes."""
    diff = SceneMsg()
    diff.is_diff = True
    diff.robot_state.is_diff = True
    diff.world.collision_objects = list(world_objects)
    diff.robot_state.attached_collision_objects = list(attached)
    return diff


class PlanningScene:
    """The move_group node's planning scene, through its apply_planning_scene/get_planning_scene services.

    Poses are PoseStamped (or anything set_pose_target accepts); an empty frame means the planning frame.
    Every change returns True when the node applied it.
    """

    def __init__(self, ns: str = "", wait_for_servers: float = 5.0) -> None:
        require_node()
        self._urdf, self._srdf = load_robot_model(ns)
        self._planning_frame = self._srdf.virtual_joint_parent or self._urdf.root_link
        waiter = ServerWaiter(wait_for_servers)
        for name in ("apply_planning_scene", "get_planning_scene"):
            waiter.service(resolve(ns, name))
        waiter.check("PlanningScene")
        self._apply = rospy.ServiceProxy(resolve(ns, "apply_planning_scene"), ApplyPlanningScene)
        self._get = rospy.ServiceProxy(resolve(ns, "get_planning_scene"), GetPlanningScene)
        self.last_error = MoveItErrorCodes()

    def _apply_diff(
        self,
        world_objects: Sequence[CollisionObject] = (),
        attached: Sequence[AttachedCollisionObject] = (),
    ) -> bool:
        try:
            response = self._apply(scene_diff(world_objects, attached))
        except (rospy.ServiceException, rospy.ROSException) as err:
            self.last_error = MoveItErrorCodes(val=MoveItErrorCodes.COMMUNICATION_FAILURE, message=str(err))
            return False
        self.last_error = response.error_code
        return bool(response.success)

    def _add_primitive(self, name: str, pose: object, shape_type: int, dimensions: list[float]) -> bool:
        obj = primitive_object(name, pose, shape_type, dimensions, self._planning_frame)
        return self._apply_diff(world_objects=[obj])

    def add_box(self, name: str, pose: object, size: Sequence[float] = (1.0, 1.0, 1.0)) -> bool:
        """Add (or replace) a box of edge lengths size (x, y, z), centred at pose."""
        return self._add_primitive(name, pose, SolidPrimitive.BOX, _check_size(size, "box size"))

    def add_sphere(self, name: str, pose: object, radius: float = 1.0) -> bool:
        """Add (or replace) a sphere centred at pose."""
        return self._add_primitive(name, pose, SolidPrimitive.SPHERE, [check_positive(radius, "sphere radius")])

    def add_cylinder(self, name: str, pose: object, height: float, radius: float) -> bool:
        """Add (or replace) a cylinder along pose's z axis, centred at pose."""
        dimensions = [check_positive(height, "cylinder height"), check_positive(radius, "cylinder radius")]
        return self._add_primitive(name, pose, SolidPrimitive.CYLINDER, dimensions)

    def add_mesh(self, name: str, pose: object, filename: str, size: Sequence[float] = (1.0, 1.0, 1.0)) -> bool:
        """Add (or replace) an STL mesh (a path or package:// URI), each axis scaled by size."""
        scale = _check_size(size, "mesh scale")
        obj = collision_object(name, pose, self._planning_frame)
        obj.meshes.append(load_stl(resolve_resource(filename), scale))
        obj.mesh_poses.append(_identity())
        return self._apply_diff(world_objects=[obj])

    def remove_world_object(self, name: str | None = None) -> bool:
        """Remove a world object (every world object with no name)."""
        names = [name] if name is not None else self.get_known_object_names()
        return self._apply_diff(world_objects=[removal(n, self._planning_frame) for n in names])

    def attach_object(self, name: str, link: str, touch_links: Sequence[str] | None = None) -> bool:
        """Attach the world object `name` rigidly to `link` at its current pose. touch_links (default:
        the link, links fixed to it and its end effector's links) may be in contact with it."""
        links = default_touch_links(self._urdf, self._srdf, link) if touch_links is None else list(touch_links)
        unknown = [lk for lk in links if lk not in self._urdf.links]
        if unknown:
            raise SixdofCommanderError(f"touch links {unknown} are not links of the robot")
        return self._apply_diff(attached=[attach_request(name, link, links)])

    def detach_object(self, name: str = "") -> bool:
        """Detach `name` (every attached object when empty) and put it back into the world."""
        return self._apply_diff(attached=[detach_request(name)])

    def _scene(self) -> SceneMsg:
        try:
            return self._get().scene
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"get_planning_scene call failed: {err}") from err

    def get_known_object_names(self) -> list[str]:
        """Ids of the world (not attached) objects."""
        return [obj.id for obj in self._scene().world.collision_objects]

    def get_attached_object_names(self) -> list[str]:
        """Ids of the objects attached to the robot."""
        return [a.object.id for a in self._scene().robot_state.attached_collision_objects]

    def get_object_poses(self, object_ids: Sequence[str] | None = None) -> dict[str, Pose]:
        """Poses of world objects (all when object_ids is None), by id; unknown ids are left out, as in MoveIt."""
        objects = self._scene().world.collision_objects
        wanted = None if object_ids is None else set(object_ids)
        return {obj.id: obj.pose for obj in objects if wanted is None or obj.id in wanted}


def resolve_resource(filename: str) -> str:
    """A file path from a path or a package://<package>/<path> URI."""
    prefix = "package://"
    if not filename.startswith(prefix):
        return filename
    package, _, relative = filename[len(prefix) :].partition("/")
    try:
        return f"{rospkg.RosPack().get_path(package)}/{relative}"
    except rospkg.ResourceNotFound as err:
        raise SixdofCommanderError(f"package '{package}' of mesh '{filename}' not found") from err
