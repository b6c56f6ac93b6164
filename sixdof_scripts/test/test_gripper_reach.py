"""The gripper's reach beyond the tcp, from the URDF's collision geometry."""

from xml.etree import ElementTree

import numpy as np
import pytest
from offline_model import parse_urdf
from sixdof_commander import SixdofCommanderError
from sixdof_commander.gripper_reach import collision_points, gripper_reach
from sixdof_commander.transforms import homogeneous

# A tip link and one finger 0.06 m long whose joint is 0.06 m along the tip's z axis (the finger spans 0.06 to
# 0.12); tcp 0.08 along the tip's z axis: the fingertip reaches 0.12 - 0.08 = 0.04 beyond the tcp.
URDF = """<robot name="hand">
  <link name="tip"><collision><geometry><cylinder radius="0.03" length="0.01"/></geometry></collision></link>
  <link name="finger">
    <collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.02 0.06"/></geometry></collision>
  </link>
  <link name="tcp"/>
  <joint name="finger_joint" type="prismatic">
    <parent link="tip"/><child link="finger"/><origin xyz="0 0 0.06"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
  </joint>
  <joint name="tcp_joint" type="fixed"><parent link="tip"/><child link="tcp"/><origin xyz="0 0 0.08"/></joint>
</robot>"""


def test_reach_is_the_fingertip_beyond_the_tcp():
    description = parse_urdf(URDF)
    tcp_in_tip = homogeneous([0.0, 0.0, 0.08], np.eye(3))
    assert gripper_reach(URDF, description, "tip", tcp_in_tip, lambda f: f) == pytest.approx(0.04)


def test_collision_points_bound_primitives():
    points = collision_points(ElementTree.fromstring(URDF), "finger", lambda f: f)
    assert points[:, 2].min() == pytest.approx(0.0)
    assert points[:, 2].max() == pytest.approx(0.06)
    assert len(collision_points(ElementTree.fromstring(URDF), "tcp", lambda f: f)) == 0


def test_unknown_link_and_bad_geometry_are_named():
    with pytest.raises(SixdofCommanderError, match="link 'nope'"):
        collision_points(ElementTree.fromstring(URDF), "nope", lambda f: f)
    bad = URDF.replace('size="0.01 0.02 0.06"', 'size="0.01 x 0.06"')
    with pytest.raises(SixdofCommanderError, match="finger.*box size"):
        collision_points(ElementTree.fromstring(bad), "finger", lambda f: f)
