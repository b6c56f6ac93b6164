"""object_markers' marker construction (no ROS master needed)."""

import pytest
from geometry_msgs.msg import Pose, Vector3
from shape_msgs.msg import SolidPrimitive
from sixdof_commander.markers import object_marker, object_markers
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker

from sixdof_msgs.msg import SimObject


def sim_object(name, shape_type, dims, color=None) -> SimObject:
    return SimObject(
        name=name, shape=SolidPrimitive(type=shape_type, dimensions=dims), color=color or ColorRGBA(1, 0, 0, 1)
    )


def test_primitives_become_markers_of_the_same_size():
    box = object_marker(sim_object("b", SolidPrimitive.BOX, [0.04, 0.05, 0.06]), Pose(), "world", 3)
    assert (box.type, box.id, box.header.frame_id) == (Marker.CUBE, 3, "world")
    assert (box.scale.x, box.scale.y, box.scale.z) == (0.04, 0.05, 0.06)
    sphere = object_marker(sim_object("s", SolidPrimitive.SPHERE, [0.025]), Pose(), "world", 0)
    assert sphere.type == Marker.SPHERE and sphere.scale.x == pytest.approx(0.05)
    cylinder = object_marker(sim_object("c", SolidPrimitive.CYLINDER, [0.10, 0.025]), Pose(), "world", 0)
    assert cylinder.type == Marker.CYLINDER
    assert (cylinder.scale.x, cylinder.scale.z) == (pytest.approx(0.05), pytest.approx(0.10))


def test_meshes_and_default_colour():
    obj = SimObject(name="m", mesh_resource="/tmp/part.stl", mesh_scale=Vector3(1, 1, 1))
    marker = object_marker(obj, Pose(), "world", 0)
    assert marker.type == Marker.MESH_RESOURCE and marker.mesh_resource == "file:///tmp/part.stl"
    assert marker.color.a == 1.0 and marker.color.r == pytest.approx(0.6)


def test_bad_shapes_are_named():
    with pytest.raises(ValueError, match="'flat'"):
        object_marker(sim_object("flat", SolidPrimitive.BOX, [0.1, 0.1]), Pose(), "world", 0)


def test_marker_ids_are_stable_and_unknown_objects_skipped():
    descriptions = {
        "b": sim_object("b", SolidPrimitive.SPHERE, [0.1]),
        "a": sim_object("a", SolidPrimitive.SPHERE, [0.1]),
    }
    array = object_markers(descriptions, ["b", "x", "a"], [Pose(), Pose(), Pose()], "world")
    assert [m.id for m in array.markers] == [1, 0]
    with pytest.raises(ValueError, match="poses"):
        object_markers(descriptions, ["a"], [], "world")
