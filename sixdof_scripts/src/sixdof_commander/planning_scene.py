"""PlanningScene: add/remove/attach collision objects of the move_group node's planning scene."""

from __future__ import annotations

from collections.abc import Sequence

import rospkg
import rospy
from geometry_msgs.msg import Pose
from moveit_msgs.msg import AttachedCollisionObject, CollisionObject, MoveItErrorCodes, PlanningSceneComponents
from moveit_msgs.msg import PlanningScene as SceneMsg
from moveit_msgs.srv import ApplyPlanningScene, GetPlanningScene, GetPlanningSceneRequest
from shape_msgs.msg import SolidPrimitive

from ._ros import ServerWaiter, load_robot_model, require_node, resolve
from ._service import SERVICE_TIMEOUT, call_service
from .error_reports import SUCCESS, CallError, ErrorReports
from .exceptions import SixdofCommanderError
from .goals import check_number, check_positive, pose_stamped_from_target
from .mesh import load_stl
from .robot_model import RobotDescription, SemanticDescription, group_links_with_descendants, resolve_group
from .transforms import matrix_from_pose


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


# The parts of the scene the queries need (GetPlanningScene's components, as MoveIt's PlanningSceneInterface asks).
WORLD_NAMES = PlanningSceneComponents.WORLD_OBJECT_NAMES
WORLD_GEOMETRY = PlanningSceneComponents.WORLD_OBJECT_GEOMETRY
ATTACHED = PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS


class PlanningScene:
    """The move_group node's planning scene: changes through its apply_planning_scene service or its planning_scene
    topic, queries through get_planning_scene.

    Poses are PoseStamped (or anything set_pose_target accepts); an empty frame means the planning frame.
    Synchronous (the default): every change is applied through the service and returns True when the node
    applied it (last_error says why not). Asynchronous: changes are published as planning-scene diffs on
    `planning_scene`, as MoveIt's C++ PlanningSceneInterface does (one topic, so they apply in order), and return
    True at once; a change move_group refuses is logged here from its error report (and kept in last_error).
    """

    def __init__(
        self,
        ns: str = "",
        wait_for_servers: float = 5.0,
        robot_description: str = "robot_description",
        synchronous: bool = True,
    ) -> None:
        require_node()
        waiter = ServerWaiter(wait_for_servers)
        for name in ("apply_planning_scene", "get_planning_scene", "get_robot_model"):
            waiter.service(resolve(ns, name))
        self._synchronous = bool(synchronous)
        self._publisher = None
        if not self._synchronous:
            self._publisher = rospy.Publisher(resolve(ns, "planning_scene"), SceneMsg, queue_size=100)
            waiter.subscriber(self._publisher)
        waiter.check("PlanningScene")
        self._urdf, self._srdf = load_robot_model(ns, robot_description, wait_for_servers)
        self._planning_frame = self._srdf.virtual_joint_parent or self._urdf.root_link
        self._apply = rospy.ServiceProxy(resolve(ns, "apply_planning_scene"), ApplyPlanningScene)
        self._get = rospy.ServiceProxy(resolve(ns, "get_planning_scene"), GetPlanningScene)
        self.last_error: CallError = SUCCESS
        self._reports = ErrorReports(ns)
        if self._publisher is not None:
            self._reports.listen(self._publisher.resolved_name, self._refused)

    # Applying changes --------------------------------------------------------------------------------
    def _refused(self, error: CallError) -> None:
        self.last_error = error
        rospy.logerr(f"PlanningScene (asynchronous): move_group refused a change: {error}")

    def _call_apply(self, diff: SceneMsg) -> bool:
        # ApplyPlanningScene answers only success; the code and the words come with the error report.
        _, self.last_error = self._reports.call(
            self._apply, diff, code=lambda r: MoveItErrorCodes.SUCCESS if r.success else 0
        )
        return self.last_error.val == MoveItErrorCodes.SUCCESS

    def _submit(self, diff: SceneMsg) -> bool:
        if self._publisher is None:
            return self._call_apply(diff)
        self._publisher.publish(diff)
        return True

    def _apply_diff(
        self,
        world_objects: Sequence[CollisionObject] = (),
        attached: Sequence[AttachedCollisionObject] = (),
    ) -> bool:
        return self._submit(scene_diff(world_objects, attached))

    def apply_planning_scene(self, planning_scene_message: SceneMsg) -> bool:
        """Apply a PlanningScene message through the service (in both modes, as MoveIt's); True if applied."""
        if not isinstance(planning_scene_message, SceneMsg):
            raise SixdofCommanderError(
                f"apply_planning_scene needs a PlanningScene message, got {type(planning_scene_message).__name__}"
            )
        return self._call_apply(planning_scene_message)

    # World objects -----------------------------------------------------------------------------------
    def _add_primitive(self, name: str, pose: object, shape_type: int, dimensions: list[float]) -> bool:
        obj = primitive_object(name, pose, shape_type, dimensions, self._planning_frame)
        return self._apply_diff(world_objects=[obj])

    def add_object(self, collision_object: CollisionObject) -> bool:
        """Apply a CollisionObject as it is (its operation: ADD, REMOVE, APPEND or MOVE)."""
        if not isinstance(collision_object, CollisionObject):
            raise SixdofCommanderError(f"add_object needs a CollisionObject, got {type(collision_object).__name__}")
        _check_name(collision_object.id)
        return self._apply_diff(world_objects=[collision_object])

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

    def _mesh_object(self, name: str, pose: object, filename: str, size: Sequence[float]) -> CollisionObject:
        scale = _check_size(size, "mesh scale")
        obj = collision_object(name, pose, self._planning_frame)
        obj.meshes.append(load_stl(resolve_resource(filename), scale))
        obj.mesh_poses.append(_identity())
        return obj

    def add_mesh(self, name: str, pose: object, filename: str, size: Sequence[float] = (1.0, 1.0, 1.0)) -> bool:
        """Add (or replace) an STL mesh (a path or package:// URI), each axis scaled by size."""
        return self._apply_diff(world_objects=[self._mesh_object(name, pose, filename, size)])

    def add_plane(self, name: str, pose: object, normal: Sequence[float] = (0, 0, 1), offset: float = 0) -> bool:
        """Refused: infinite planes are not collision objects of sixdof's planning scene (use a large thin box)."""
        raise SixdofCommanderError(
            "add_plane() is not available on sixdof: the planning scene has no infinite planes; "
            "add a large thin box with add_box() instead"
        )

    def remove_world_object(self, name: str | None = None) -> bool:
        """Remove a world object (every world object with no name)."""
        names = [name] if name is not None else self.get_known_object_names()
        return self._apply_diff(world_objects=[removal(n, self._planning_frame) for n in names])

    # Attached objects --------------------------------------------------------------------------------
    def _touch_links(self, link: str, touch_links: Sequence[str] | None) -> list[str]:
        links = default_touch_links(self._urdf, self._srdf, link) if touch_links is None else list(touch_links)
        unknown = [lk for lk in links if lk not in self._urdf.links]
        if unknown:
            raise SixdofCommanderError(f"touch links {unknown} are not links of the robot")
        return links

    def attach_object(self, name: str, link: str, touch_links: Sequence[str] | None = None) -> bool:
        """Attach the world object `name` rigidly to `link` at its current pose. touch_links (default:
        the link, links fixed to it and its end effector's links) may be in contact with it."""
        return self._apply_diff(attached=[attach_request(name, link, self._touch_links(link, touch_links))])

    def attach_primitive(
        self, name: str, link: str, pose: object, shape: SolidPrimitive, touch_links: Sequence[str] | None = None
    ) -> bool:
        """Attach the solid primitive `name` centred at pose to `link`, replacing a world or attached object of
        that name (e.g. a world object whose scene pose lags behind where the gripper holds it); touch_links as
        attach_object."""
        attached = attach_request(name, link, self._touch_links(link, touch_links))
        attached.object = primitive_object(name, pose, shape.type, list(shape.dimensions), self._planning_frame)
        return self._apply_diff(attached=[attached])

    def attach_collision_object(self, attached_collision_object: AttachedCollisionObject) -> bool:
        """Apply an AttachedCollisionObject as it is (with shapes: a new object; without: a world object)."""
        if not isinstance(attached_collision_object, AttachedCollisionObject):
            raise SixdofCommanderError(
                f"needs an AttachedCollisionObject, got {type(attached_collision_object).__name__}"
            )
        self._touch_links(attached_collision_object.link_name, attached_collision_object.touch_links)
        return self._apply_diff(attached=[attached_collision_object])

    def _attach_existing(self, link: str, name: str, touch_links: Sequence[str]) -> bool:
        links = self._touch_links(link, list(touch_links) or [link])
        return self._apply_diff(attached=[attach_request(name, link, links)])

    def _attach_new(self, link: str, obj: CollisionObject, touch_links: Sequence[str]) -> bool:
        attached = AttachedCollisionObject()
        attached.link_name = link
        attached.object = obj
        attached.touch_links = self._touch_links(link, list(touch_links) or [link])
        return self._apply_diff(attached=[attached])

    def attach_box(
        self,
        link: str,
        name: str,
        pose: object = None,
        size: Sequence[float] = (1.0, 1.0, 1.0),
        touch_links: Sequence[str] = (),
    ) -> bool:
        """Attach a new box at pose to `link` (without a pose: attach the existing world object `name`).
        touch_links default to [link], as in MoveIt."""
        if pose is None:
            return self._attach_existing(link, name, touch_links)
        box = primitive_object(name, pose, SolidPrimitive.BOX, _check_size(size, "box size"), self._planning_frame)
        return self._attach_new(link, box, touch_links)

    def attach_mesh(
        self,
        link: str,
        name: str,
        pose: object = None,
        filename: str = "",
        size: Sequence[float] = (1.0, 1.0, 1.0),
        touch_links: Sequence[str] = (),
    ) -> bool:
        """Attach a new STL mesh at pose to `link` (without pose and filename: the existing world object)."""
        if pose is None or not filename:
            return self._attach_existing(link, name, touch_links)
        return self._attach_new(link, self._mesh_object(name, pose, filename, size), touch_links)

    def detach_object(self, name: str = "") -> bool:
        """Detach `name` (every attached object when empty) and put it back into the world."""
        return self._apply_diff(attached=[detach_request(name)])

    def remove_attached_object(self, link: str | None = None, name: str | None = None) -> bool:
        """Detach `name`, or every object attached to `link`, or every attached object (neither given). Detached
        objects return to the world, as in MoveIt (remove_world_object removes them)."""
        if name is not None:
            return self.detach_object(_check_name(name))
        if link is None:
            return self.detach_object("")
        if link not in self._urdf.links:
            raise SixdofCommanderError(f"link '{link}' is not a link of the robot")
        attached = self._scene(ATTACHED).robot_state.attached_collision_objects
        return self._apply_diff(attached=[detach_request(a.object.id) for a in attached if a.link_name == link])

    def clear(self) -> bool:
        """Remove every attached and world object: detach them all, then remove them with the world's objects
        (two diffs, applied in this order in both modes)."""
        names = self.get_known_object_names() + self.get_attached_object_names()
        detached = self.detach_object("")
        removed = self._apply_diff(world_objects=[removal(n, self._planning_frame) for n in names])
        return detached and removed

    # Queries -----------------------------------------------------------------------------------------
    def _scene(self, components: int) -> SceneMsg:
        """The parts `components` (PlanningSceneComponents flags) of move_group's scene."""
        request = GetPlanningSceneRequest()
        request.components.components = components
        try:
            return call_service(self._get, request, SERVICE_TIMEOUT).scene
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"get_planning_scene call failed: {err}") from err

    def _world(self, with_type: bool = False) -> list[CollisionObject]:
        """The world's objects with their geometry; with_type: only those with a type (`type.key` set)."""
        objects = self._scene(WORLD_GEOMETRY).world.collision_objects
        return [obj for obj in objects if obj.type.key] if with_type else list(objects)

    def get_known_object_names(self, with_type: bool = False) -> list[str]:
        """Ids of the world (not attached) objects; with_type: only those with a recognised type (`type.key`)."""
        if with_type:
            return [obj.id for obj in self._world(with_type=True)]
        return [obj.id for obj in self._scene(WORLD_NAMES).world.collision_objects]

    def get_known_object_names_in_roi(
        self,
        minx: float,
        miny: float,
        minz: float,
        maxx: float,
        maxy: float,
        maxz: float,
        with_type: bool = False,
    ) -> list[str]:
        """Ids of world objects all of whose shapes' origins lie in the box (planning frame), as MoveIt's;
        with_type: only those with a recognised type."""
        bounds = [check_number(v, f"ROI bound {i}") for i, v in enumerate((minx, miny, minz, maxx, maxy, maxz))]
        names = []
        for obj in self._world(with_type):
            origin = matrix_from_pose(obj.pose)
            shapes = list(obj.primitive_poses) + list(obj.mesh_poses)
            inside = bool(shapes)
            for shape in shapes:
                point = (origin @ matrix_from_pose(shape))[:3, 3]
                inside = inside and all(bounds[i] <= point[i] <= bounds[i + 3] for i in range(3))
            if inside:
                names.append(obj.id)
        return names

    def get_attached_object_names(self) -> list[str]:
        """Ids of the objects attached to the robot."""
        return [a.object.id for a in self._scene(ATTACHED).robot_state.attached_collision_objects]

    def get_object_poses(self, object_ids: Sequence[str] | None = None) -> dict[str, Pose]:
        """Poses of world objects (all when object_ids is None), by id; unknown ids are left out, as in MoveIt."""
        wanted = None if object_ids is None else set(object_ids)
        return {obj.id: obj.pose for obj in self._world() if wanted is None or obj.id in wanted}

    def get_objects(self, object_ids: Sequence[str] | None = None) -> dict[str, CollisionObject]:
        """World objects by id (all when object_ids is empty or None)."""
        wanted = set(object_ids) if object_ids else None
        return {o.id: o for o in self._world() if wanted is None or o.id in wanted}

    def get_attached_objects(
        self, object_ids: Sequence[str] | None = None
    ) -> dict[str, AttachedCollisionObject]:
        """Attached objects by id (all when object_ids is empty or None)."""
        wanted = set(object_ids) if object_ids else None
        attached = self._scene(ATTACHED).robot_state.attached_collision_objects
        return {a.object.id: a for a in attached if wanted is None or a.object.id in wanted}


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
