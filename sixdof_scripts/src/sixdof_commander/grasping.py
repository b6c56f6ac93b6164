"""Top-down grasp geometry: where the tool goes to pick an object and to put it down.

Pure functions on numpy transforms (4x4, world frame); the gripper's geometry (its TCP in the arm's tip link, the
closing axis, opening, finger reach and palm depth) is passed in as a GraspSpec, which the caller builds from the
config package's grasping information (move_group's get_robot_model: `grasp_spec`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from shape_msgs.msg import SolidPrimitive

from .exceptions import SixdofCommanderError
from .robot_model import GripperModel
from .transforms import homogeneous, matrix_from_quaternion, matrix_from_rpy


@dataclass(frozen=True)
class GraspSpec:
    """What a grasp needs from the robot. tcp_in_tip: 4x4 pose of the grasp frame (TCP: z along the approach, at the
    pads' centre depth) in the arm's tip link; finger_axis: the fingers' closing direction in the TCP frame;
    max_width: widest graspable object (the opening between the pads); reach: how far the fingers extend beyond the
    tcp along its z axis, which must stay `clearance` above the surface the object stands on; palm_depth: how far an
    object between the pads may reach back from the tcp before the palm (its top stays `clearance` below it);
    max_grasp_depth: how far below its top a tall object is held; min_grip: how far down the object's side from
    its top the fingers must reach."""

    tcp_in_tip: np.ndarray
    finger_axis: np.ndarray
    max_width: float
    clearance: float = 0.005
    max_grasp_depth: float = 0.03
    reach: float = 0.0
    palm_depth: float = math.inf
    min_grip: float = 0.005


def grasp_spec(gripper: GripperModel, parent_in_tip: np.ndarray) -> GraspSpec:
    """The GraspSpec of a gripper's grasping information; parent_in_tip: its parent link in the arm's tip link."""
    tcp_in_tip = parent_in_tip @ gripper.tcp
    closing = gripper.tcp[:3, :3].T @ gripper.closing_direction
    return GraspSpec(
        tcp_in_tip=tcp_in_tip,
        finger_axis=closing / np.linalg.norm(closing),
        max_width=gripper.max_opening,
        reach=gripper.finger_reach,
        palm_depth=gripper.palm_depth,
    )


@dataclass(frozen=True)
class ObjectGeometry:
    """An object's pose (4x4, world) and its upright footprint: the vertical extent and the horizontal
    axes that may be squeezed (unit xy directions with the object's width along each)."""

    pose: np.ndarray
    height: float
    squeeze_axes: tuple[tuple[np.ndarray, float], ...]  # empty: any direction (round objects)
    round_width: float = 0.0


def wrap_angle(angle: float) -> float:
    """angle in [-pi, pi)."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def pose_matrix(position: tuple[float, float, float], quaternion: tuple[float, float, float, float]) -> np.ndarray:
    """4x4 transform from a position and a quaternion (x, y, z, w)."""
    return homogeneous(position, matrix_from_quaternion(quaternion))


def object_geometry(pose: np.ndarray, shape: SolidPrimitive) -> ObjectGeometry:
    """The upright footprint of a box, cylinder or sphere at pose."""
    rotation = pose[:3, :3]
    if shape.type == SolidPrimitive.SPHERE:
        (radius,) = _dimensions(shape, 1, "sphere")
        return ObjectGeometry(pose=pose, height=2.0 * radius, squeeze_axes=(), round_width=2.0 * radius)
    if shape.type == SolidPrimitive.CYLINDER:
        height, radius = _dimensions(shape, 2, "cylinder")
        if abs(rotation[2, 2]) < math.cos(math.radians(10.0)):
            raise SixdofCommanderError("the cylinder is not upright: only upright cylinders are grasped from the top")
        return ObjectGeometry(pose=pose, height=height, squeeze_axes=(), round_width=2.0 * radius)
    if shape.type == SolidPrimitive.BOX:
        sizes = _dimensions(shape, 3, "box")
        vertical = int(np.argmax(np.abs(rotation[2, :])))
        if abs(rotation[2, vertical]) < math.cos(math.radians(10.0)):
            raise SixdofCommanderError("the box has no face on top (tilted): it cannot be grasped from the top")
        axes = []
        for i in range(3):
            if i != vertical:
                direction = np.array([rotation[0, i], rotation[1, i], 0.0])
                axes.append((direction / np.linalg.norm(direction), sizes[i]))
        return ObjectGeometry(pose=pose, height=sizes[vertical], squeeze_axes=tuple(axes))
    raise SixdofCommanderError(f"cannot grasp a shape of type {shape.type} (only box, cylinder, sphere)")


def _dimensions(shape: SolidPrimitive, count: int, what: str) -> list[float]:
    dims = list(shape.dimensions)
    if len(dims) < count or any(not math.isfinite(d) or d <= 0.0 for d in dims[:count]):
        raise SixdofCommanderError(f"{what} needs {count} positive dimensions, got {dims}")
    return dims[:count]


def top_down_rotation(yaw: float) -> np.ndarray:
    """Tool orientation with its z axis pointing down, turned by yaw about the world z axis."""
    return matrix_from_rpy(math.pi, 0.0, yaw)


def preferred_yaw(x: float, y: float) -> float:
    """The wrist yaw that reaches (x, y) from the base without twisting (the paper's home pose: yaw pi)."""
    return wrap_angle(math.atan2(y, x) + math.pi)


def grasp_yaw(geometry: ObjectGeometry, spec: GraspSpec) -> tuple[float, float]:
    """(yaw, width): the top-down yaw whose finger axis squeezes a graspable width of the object,
    nearest the preferred wrist yaw at the object's position."""
    limit = spec.max_width - 2.0 * spec.clearance
    x, y = geometry.pose[0, 3], geometry.pose[1, 3]
    preferred = preferred_yaw(x, y)
    if not geometry.squeeze_axes:
        if geometry.round_width > limit:
            raise SixdofCommanderError(
                f"object width {geometry.round_width:.3f} m exceeds the gripper's opening {limit:.3f} m"
            )
        return preferred, geometry.round_width
    # The finger axis at yaw 0, in the world's xy plane: yaw turns it by the same angle.
    axis0 = top_down_rotation(0.0) @ spec.finger_axis
    if math.hypot(axis0[0], axis0[1]) < 1e-6:
        raise SixdofCommanderError("the gripper's finger axis is along the tool axis: no top-down grasp")
    axis_angle = math.atan2(axis0[1], axis0[0])
    candidates = []
    for direction, width in geometry.squeeze_axes:
        if width <= limit:
            base = math.atan2(direction[1], direction[0]) - axis_angle
            for flip in (0.0, math.pi):
                yaw = wrap_angle(base + flip)
                candidates.append((abs(wrap_angle(yaw - preferred)), yaw, width))
    if not candidates:
        widths = ", ".join(f"{w:.3f}" for _, w in geometry.squeeze_axes)
        raise SixdofCommanderError(f"object widths {widths} m all exceed the gripper's opening {limit:.3f} m")
    _, yaw, width = min(candidates, key=lambda c: c[0])
    return yaw, width


def grasp_tcp_pose(geometry: ObjectGeometry, spec: GraspSpec) -> tuple[np.ndarray, float]:
    """(tcp pose, width squeezed): tool z down, the tcp (the pads' centre) at the object's middle height but no deeper
    than max_grasp_depth below its top, high enough for the fingertips to stay `clearance` above the object's bottom
    (the surface it stands on) and for the object's top to stay `clearance` below the palm."""
    yaw, width = grasp_yaw(geometry, spec)
    centre = geometry.pose[:3, 3]
    bottom, top = centre[2] - geometry.height / 2.0, centre[2] + geometry.height / 2.0
    z = max(
        centre[2],
        top - spec.max_grasp_depth,
        bottom + spec.reach + spec.clearance,
        top - spec.palm_depth + spec.clearance,
    )
    grip = top - max(bottom, z - spec.reach)  # how far down the object's side the fingers reach
    if grip < spec.min_grip:
        raise SixdofCommanderError(
            f"object height {geometry.height:.3f} m is too low for a top-down grasp: the fingers reach "
            f"{spec.reach:.3f} m beyond the tcp and must stay {spec.clearance:.3f} m above the support, leaving "
            f"{max(grip, 0.0) * 1000:.1f} mm of grip (at least {spec.min_grip * 1000:.1f} mm needed)"
        )
    return homogeneous([centre[0], centre[1], z], top_down_rotation(yaw)), width


def tip_pose(tcp_pose: np.ndarray, spec: GraspSpec) -> np.ndarray:
    """The arm tip link's pose that puts the tcp at tcp_pose."""
    return tcp_pose @ np.linalg.inv(spec.tcp_in_tip)


def raised(pose: np.ndarray, height: float) -> np.ndarray:
    """pose moved up by height along the world z axis."""
    result = pose.copy()
    result[2, 3] += height
    return result


def uprighting(rotation: np.ndarray) -> np.ndarray:
    """The least rotation (world frame) that turns the axis of `rotation` nearest the vertical (any of its six
    directions: a box may stand on any face) onto +z."""
    axes = np.hstack([rotation, -rotation])
    up = axes[:, int(np.argmax(axes[2, :]))]
    v = np.cross(up, [0.0, 0.0, 1.0])
    s, c = np.linalg.norm(v), up[2]
    if s < 1e-12:
        return np.eye(3)
    k = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    return np.eye(3) + k + k @ k * ((1.0 - c) / s**2)


def place_tcp_pose(target: np.ndarray, object_in_tcp: np.ndarray, clearance: float) -> np.ndarray:
    """tcp pose that puts the held object's centre at target (xyz) plus clearance above it, tool z down, with the
    wrist yaw preferred at the target. object_in_tcp: the object's centre (a homogeneous 4-vector) or its pose
    (4x4) in the tcp frame; given a pose, the tool leans as the object leans in the hand, so that the object comes
    down upright (MoveIt's place: the tool's pose is the object's place pose times the inverse of its pose in the
    tool)."""
    rotation = top_down_rotation(preferred_yaw(target[0], target[1]))
    held = np.asarray(object_in_tcp, dtype=float)
    if held.shape == (4, 4):
        rotation = uprighting(rotation @ held[:3, :3]) @ rotation
        held = held[:, 3]
    position = np.asarray(target, dtype=float) + np.array([0.0, 0.0, clearance]) - rotation @ held[:3]
    return homogeneous(position, rotation)
