"""Conversions between ROS messages and the detector's numpy arrays and dataclasses."""

from __future__ import annotations

import math

import numpy as np
from geometry_msgs.msg import Pose, PoseStamped, TransformStamped, Vector3
from sensor_msgs.msg import PointCloud2, PointField
from shape_msgs.msg import SolidPrimitive
from sixdof_commander.transforms import matrix_from_pose, quaternion_from_matrix
from std_msgs.msg import ColorRGBA, Header

from sixdof_msgs.msg import DetectedObject, SimObject

from .detection import Detection
from .world import StaticBox

_FLOAT32 = PointField.FLOAT32


def cloud_arrays(cloud: PointCloud2) -> tuple[np.ndarray, np.ndarray]:
    """Points (HxWx3 float64, NaN where nothing was hit) and colours (HxWx3 in [0, 1]) of an organized
    PointCloud2 with float32 fields x, y, z and a PCL-packed rgb (0x00RRGGBB in the bits of a float32)."""
    fields = {f.name: f for f in cloud.fields}
    for name in ("x", "y", "z", "rgb"):
        if name not in fields or fields[name].datatype != _FLOAT32:
            raise ValueError(f"point cloud needs float32 fields x, y, z and rgb; '{name}' is missing or not float32")
    if cloud.height < 2:
        raise ValueError(f"point cloud must be organized (height > 1), got height {cloud.height}")
    if cloud.is_bigendian:
        raise ValueError("big-endian point clouds are not supported")
    raw = np.frombuffer(cloud.data, dtype=np.uint8)
    expected = cloud.row_step * cloud.height
    if len(raw) < expected or cloud.row_step < cloud.point_step * cloud.width:
        raise ValueError(f"point cloud data has {len(raw)} bytes, its size says {expected}")
    rows = raw[:expected].reshape(cloud.height, cloud.row_step)[:, : cloud.point_step * cloud.width]
    cells = rows.reshape(cloud.height, cloud.width, cloud.point_step)

    def column(name: str, dtype: str) -> np.ndarray:
        offset = fields[name].offset
        return cells[:, :, offset : offset + 4].copy().view(dtype)[:, :, 0]

    points = np.stack([column("x", "<f4"), column("y", "<f4"), column("z", "<f4")], axis=-1).astype(np.float64)
    packed = column("rgb", "<u4")
    colors = np.stack([(packed >> 16) & 0xFF, (packed >> 8) & 0xFF, packed & 0xFF], axis=-1) / 255.0
    return points, colors


def transform_points(points: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """Apply a 4x4 transform to ...x3 points (NaN stays NaN)."""
    return points @ matrix[:3, :3].T + matrix[:3, 3]


def transform_matrix(transform: TransformStamped) -> np.ndarray:
    """4x4 matrix of a tf transform."""
    t = transform.transform.translation
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = t.x, t.y, t.z
    pose.orientation = transform.transform.rotation
    return matrix_from_pose(pose)


def yaw_pose(position: tuple[float, float, float], yaw: float) -> Pose:
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = position
    pose.orientation.z = math.sin(yaw / 2.0)
    pose.orientation.w = math.cos(yaw / 2.0)
    return pose


def primitive(detection: Detection) -> SolidPrimitive:
    """The detection's shape as a SolidPrimitive (BOX [x, y, z], CYLINDER [height, radius], SPHERE [radius])."""
    sx, sy, sz = detection.size
    if detection.shape == "box":
        return SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[sx, sy, sz])
    if detection.shape == "cylinder":
        return SolidPrimitive(type=SolidPrimitive.CYLINDER, dimensions=[sz, sx / 2.0])
    if detection.shape == "sphere":
        return SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[sx / 2.0])
    raise ValueError(f"unknown detected shape '{detection.shape}'")


def detected_object(
    object_id: str,
    detection: Detection,
    header: Header,
    velocity: tuple[float, float, float] | None = None,
) -> DetectedObject:
    msg = DetectedObject()
    msg.id = object_id
    msg.label = detection.label
    msg.color = detection.color
    msg.rgb = ColorRGBA(*detection.rgb, 1.0)
    msg.shape = primitive(detection)
    msg.size = Vector3(*detection.size)
    msg.pose = PoseStamped(header=header, pose=yaw_pose(detection.position, detection.yaw))
    msg.score = detection.score
    msg.point_count = detection.point_count
    msg.velocity_valid = velocity is not None
    if velocity is not None:
        msg.velocity = Vector3(*velocity)
    return msg


def sim_object(object_id: str, detection: Detection) -> SimObject:
    """A SimObject description of a detection, so that the scene mirror's and the object markers' helpers
    (sixdof_commander.scene_mirror, sixdof_commander.markers) serve detected objects too."""
    return SimObject(
        name=object_id,
        shape=primitive(detection),
        pose=yaw_pose(detection.position, detection.yaw),
        color=ColorRGBA(*detection.rgb, 0.8),
        is_static=False,
    )


def static_sim_object(box: StaticBox) -> SimObject:
    """A SimObject of a static box of the scenery."""
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = box.centre
    q = quaternion_from_matrix(box.rotation)
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = (float(v) for v in q)
    return SimObject(
        name=box.name,
        shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=list(box.size)),
        pose=pose,
        is_static=True,
    )
