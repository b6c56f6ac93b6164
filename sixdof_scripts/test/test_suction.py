"""A suction tool in the commander: its grasping information as get_robot_model serves it, and where the cup's face
goes to pick an object (the centre of its top face, tool down)."""

import math

import numpy as np
import pytest
from geometry_msgs.msg import Vector3
from shape_msgs.msg import SolidPrimitive
from sixdof_commander.grasping import object_geometry
from sixdof_commander.robot_model import gripper_from_msg
from sixdof_commander.suction import suction_tcp_pose
from sixdof_commander.transforms import homogeneous, matrix_from_rpy

from sixdof_msgs.msg import RobotModelGripper


def test_the_cup_and_its_vacuum_come_from_the_message():
    msg = RobotModelGripper(group="gripper", end_effector="hand", tcp_frame="tcp", parent_link="link6",
                            approach_direction=Vector3(0.0, 0.0, 1.0), suction_cup="tcp",
                            vacuum_controller="gripper_controller", max_payload=0.5)
    msg.tcp.position.z, msg.tcp.orientation.w = 0.042, 1.0
    gripper = gripper_from_msg(msg)
    assert (gripper.suction_cup, gripper.vacuum_controller, gripper.max_payload) == ("tcp", "gripper_controller", 0.5)
    assert gripper.open_positions == {} and gripper.tcp[2, 3] == pytest.approx(0.042)


@pytest.mark.parametrize(("shape", "dimensions", "top"), [
    (SolidPrimitive.BOX, [0.04, 0.04, 0.04], 0.04),
    (SolidPrimitive.CYLINDER, [0.06, 0.02], 0.06),
    (SolidPrimitive.SPHERE, [0.03], 0.06),
])
def test_the_face_goes_on_the_centre_of_the_top(shape, dimensions, top):
    centre = [0.4, -0.15, top / 2.0]
    pose = homogeneous(centre, matrix_from_rpy(0.0, 0.0, 0.7))
    tcp = suction_tcp_pose(object_geometry(pose, SolidPrimitive(type=shape, dimensions=dimensions)))
    assert tcp[:3, 3] == pytest.approx([0.4, -0.15, top])
    # Tool z straight down, the wrist yaw the one preferred at the object (pointing away from the base).
    assert tcp[:3, 2] == pytest.approx([0.0, 0.0, -1.0])
    assert math.atan2(tcp[1, 0], tcp[0, 0]) == pytest.approx(math.atan2(-0.15, 0.4) + math.pi)
    assert np.allclose(tcp[:3, :3].T @ tcp[:3, :3], np.eye(3))
