"""rviz markers of objects described as the simulator describes them (SimObject: shape or mesh, colour): the
simulator's objects (sixdof_bringup's object_markers) and the detected ones (sixdof_perception)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from geometry_msgs.msg import Pose, Vector3
from shape_msgs.msg import SolidPrimitive
from visualization_msgs.msg import Marker, MarkerArray

from sixdof_msgs.msg import SimObject


def object_marker(obj: SimObject, pose: Pose, frame_id: str, marker_id: int) -> Marker:
    """A marker drawing the object's primitive or mesh at pose, in its colour (grey when transparent black)."""
    marker = Marker()
    marker.header.frame_id = frame_id
    marker.ns = "sixdof_sim_objects"
    marker.id = marker_id
    marker.action = Marker.ADD
    marker.pose = pose
    marker.color = obj.color
    if marker.color.a == 0.0:
        marker.color.r = marker.color.g = marker.color.b = 0.6
        marker.color.a = 1.0
    if obj.mesh_resource:
        marker.type = Marker.MESH_RESOURCE
        uri = obj.mesh_resource
        marker.mesh_resource = uri if "://" in uri else f"file://{uri}"
        marker.scale = obj.mesh_scale
        return marker
    dims = list(obj.shape.dimensions)
    if obj.shape.type == SolidPrimitive.BOX and len(dims) == 3:
        marker.type = Marker.CUBE
        marker.scale = Vector3(*dims)
    elif obj.shape.type == SolidPrimitive.SPHERE and len(dims) == 1:
        marker.type = Marker.SPHERE
        marker.scale = Vector3(2.0 * dims[0], 2.0 * dims[0], 2.0 * dims[0])
    elif obj.shape.type == SolidPrimitive.CYLINDER and len(dims) == 2:
        # SolidPrimitive cylinders are [height, radius]; the marker scales diameter, diameter, height.
        marker.type = Marker.CYLINDER
        marker.scale = Vector3(2.0 * dims[1], 2.0 * dims[1], dims[0])
    else:
        raise ValueError(f"object '{obj.name}': unsupported shape type {obj.shape.type} with dimensions {dims}")
    return marker


def object_markers(
    descriptions: Mapping[str, SimObject], names: Sequence[str], poses: Sequence[Pose], frame_id: str
) -> MarkerArray:
    """Markers of the named objects at their poses; ids follow the sorted names so they stay stable."""
    if len(names) != len(poses):
        raise ValueError(f"{len(names)} names but {len(poses)} poses")
    ids = {name: i for i, name in enumerate(sorted(descriptions))}
    array = MarkerArray()
    for name, pose in zip(names, poses, strict=True):
        if name in descriptions:
            array.markers.append(object_marker(descriptions[name], pose, frame_id, ids[name]))
    return array
