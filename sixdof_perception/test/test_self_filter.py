"""The self filter's link boxes from the collision geometry of move_group's model (the get_robot_model response's
sixdof_msgs/RobotModelLinkGeometry messages, built here), posed at the links and around a hand."""

import numpy as np
from geometry_msgs.msg import Point, Pose
from shape_msgs.msg import Mesh, MeshTriangle, SolidPrimitive

from sixdof_msgs.msg import RobotModelLinkGeometry
from sixdof_perception.self_filter import hand_box, link_boxes, posed_boxes


def pose(x=0.0, y=0.0, z=0.0, qz=0.0, qw=1.0) -> Pose:
    result = Pose()
    result.position.x, result.position.y, result.position.z = x, y, z
    result.orientation.z, result.orientation.w = qz, qw
    return result


def translation(x, y, z) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, 3] = (x, y, z)
    return matrix


# A base box off its origin, a link with a sphere and a mesh (two vertices apart along x), a link with none.
GEOMETRY = [
    RobotModelLinkGeometry(
        link_name="base",
        primitives=[SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.2, 0.4, 0.1])],
        primitive_poses=[pose(z=0.05)],
    ),
    RobotModelLinkGeometry(
        link_name="finger",
        primitives=[SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[0.01])],
        primitive_poses=[pose()],
        meshes=[
            Mesh(
                vertices=[Point(0.0, 0.0, 0.0), Point(0.05, 0.0, 0.0), Point(0.0, 0.0, 0.02)],
                triangles=[MeshTriangle(vertex_indices=[0, 1, 2])],
            )
        ],
        # Turned a quarter about z: the mesh's x axis is the link's y axis.
        mesh_poses=[pose(z=0.1, qz=np.sqrt(0.5), qw=np.sqrt(0.5))],
    ),
    RobotModelLinkGeometry(link_name="bare"),
]


def test_link_boxes_bound_primitives_and_meshes_in_the_link_frame():
    boxes = link_boxes(GEOMETRY)
    assert sorted(boxes) == ["base", "finger"]
    centre, half = boxes["base"]
    np.testing.assert_allclose(centre, [0.0, 0.0, 0.05], atol=1e-12)
    np.testing.assert_allclose(half, [0.1, 0.2, 0.05], atol=1e-12)
    centre, half = boxes["finger"]
    # x and y: the sphere's -0.01..0.01 and the turned mesh's 0..0.05 along y; z: the sphere's -0.01 to 0.12.
    np.testing.assert_allclose(centre - half, [-0.01, -0.01, -0.01], atol=1e-9)
    np.testing.assert_allclose(centre + half, [0.01, 0.05, 0.12], atol=1e-9)


def test_posed_and_hand_boxes_follow_the_links():
    boxes = link_boxes(GEOMETRY)
    poses = {"base": translation(1.0, 0.0, 0.0), "finger": translation(1.0, 0.0, 0.5)}
    posed = {tuple(np.round(box.centre, 9)) for box in posed_boxes(boxes, poses)}
    assert posed == {(1.0, 0.0, 0.05), (1.0, 0.02, 0.555)}
    # The hand box around base and finger, aligned with base: z from base's 0 to finger's 0.5 + 0.12.
    box = hand_box(boxes, poses, "base", ["base", "finger", "bare"])
    np.testing.assert_allclose(box.centre - box.half, [0.9, -0.2, 0.0], atol=1e-9)
    np.testing.assert_allclose(box.centre + box.half, [1.1, 0.2, 0.62], atol=1e-9)
    assert hand_box(boxes, poses, "missing", ["finger"]) is None
