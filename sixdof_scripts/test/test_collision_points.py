"""The points that bound a link's collision shapes, from the collision geometry of move_group's model (built here
as the get_robot_model response's sixdof_msgs/RobotModelLinkGeometry messages): what the perception node's self
filter is made of."""

import dataclasses

import numpy as np
import pytest
from core_model import load_model
from geometry_msgs.msg import Point, Pose
from shape_msgs.msg import Mesh, MeshTriangle, SolidPrimitive
from sixdof_commander import SixdofCommanderError
from sixdof_commander.robot_model import geometry_points, primitive_points
from sixdof_commander.transforms import quaternion_from_rpy

from sixdof_msgs.msg import RobotModelLinkGeometry

# A tip link, one finger below it and a frame without geometry.
URDF = """<robot name="hand">
  <link name="tip"/><link name="finger"/><link name="tcp"/>
  <joint name="finger_joint" type="prismatic">
    <parent link="tip"/><child link="finger"/><origin xyz="0 0 0.06"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
  </joint>
  <joint name="tcp_joint" type="fixed"><parent link="tip"/><child link="tcp"/><origin xyz="0 0 0.08"/></joint>
</robot>"""


def pose(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)) -> Pose:
    result = Pose()
    result.position.x, result.position.y, result.position.z = xyz
    q = quaternion_from_rpy(*rpy)
    result.orientation.x, result.orientation.y, result.orientation.z, result.orientation.w = q
    return result


def primitive(kind: int, *dimensions: float) -> SolidPrimitive:
    return SolidPrimitive(type=kind, dimensions=list(dimensions))


# The finger: a box from 0 to 0.06 along z (its centre at 0.03).
FINGER = RobotModelLinkGeometry(
    link_name="finger",
    primitives=[primitive(SolidPrimitive.BOX, 0.01, 0.02, 0.06)],
    primitive_poses=[pose((0.0, 0.0, 0.03))],
)


def hand(geometry=None):
    return dataclasses.replace(load_model(URDF)[0], collision={"finger": FINGER} if geometry is None else geometry)


def test_geometry_points_bound_every_primitive_in_the_link_frame():
    points = geometry_points(FINGER)
    np.testing.assert_allclose(points.min(axis=0), [-0.005, -0.01, 0.0], atol=1e-12)
    np.testing.assert_allclose(points.max(axis=0), [0.005, 0.01, 0.06], atol=1e-12)
    # A cylinder (height 0.4, radius 0.1) turned onto the x axis spans x by its height.
    turned = RobotModelLinkGeometry(
        link_name="arm",
        primitives=[primitive(SolidPrimitive.CYLINDER, 0.4, 0.1), primitive(SolidPrimitive.SPHERE, 0.05)],
        primitive_poses=[pose((0.2, 0.0, 0.0), (0.0, np.pi / 2.0, 0.0)), pose((0.0, 0.0, 0.3))],
    )
    points = geometry_points(turned)
    np.testing.assert_allclose(points.min(axis=0), [-0.05, -0.1, -0.1], atol=1e-12)
    np.testing.assert_allclose(points.max(axis=0), [0.4, 0.1, 0.35], atol=1e-12)
    assert geometry_points(RobotModelLinkGeometry(link_name="empty")).shape == (0, 3)


def test_mesh_vertices_count_at_their_pose():
    # A mesh 0.07 along the link's z axis, its vertices up to 0.05 along its own: upright they reach 0.12, turned
    # over (roll pi) 0.02.
    mesh = Mesh(
        vertices=[Point(0.0, 0.0, 0.0), Point(0.0, 0.0, 0.05), Point(0.01, 0.0, 0.0)],
        triangles=[MeshTriangle(vertex_indices=[0, 1, 2])],
    )
    for rpy, (low, high) in (((0.0, 0.0, 0.0), (0.07, 0.12)), ((np.pi, 0.0, 0.0), (0.02, 0.07))):
        finger = RobotModelLinkGeometry(link_name="finger", meshes=[mesh], mesh_poses=[pose((0.0, 0.0, 0.07), rpy)])
        z = hand({"finger": finger}).collision_points("finger")[:, 2]
        assert (z.min(), z.max()) == pytest.approx((low, high))


def test_links_without_geometry_have_no_points_and_unknown_links_are_named():
    assert hand().collision_points("tcp").shape == (0, 3)
    with pytest.raises(SixdofCommanderError, match="link 'nope'"):
        hand().collision_points("nope")


def test_a_model_queried_without_geometry_says_so():
    with pytest.raises(SixdofCommanderError, match="collision_geometry=True"):
        load_model(URDF)[0].collision_points("finger")


def test_bad_primitives_are_named():
    with pytest.raises(SixdofCommanderError, match="type 4 is not a box, sphere or cylinder"):
        primitive_points(primitive(SolidPrimitive.CONE, 0.1, 0.1))
    with pytest.raises(SixdofCommanderError, match=r"bad dimensions \[0.1, 0.2\]"):
        primitive_points(primitive(SolidPrimitive.BOX, 0.1, 0.2))
    with pytest.raises(SixdofCommanderError, match="bad dimensions"):
        primitive_points(primitive(SolidPrimitive.SPHERE, float("nan")))
