"""What scripts take from the config package: the gripper's grasping information (as get_robot_model serves it), the
arm group it is the end effector of, the home state and the grasp geometry in the arm's tip link."""

import dataclasses
import math

import numpy as np
import pytest
from geometry_msgs.msg import Vector3
from sixdof_commander import SixdofCommanderError
from sixdof_commander.grasping import grasp_spec
from sixdof_commander.package_defaults import arm_group, find_gripper, home_state, link_in_link
from sixdof_commander.robot_model import gripper_from_msg
from sixdof_commander.transforms import homogeneous, matrix_from_rpy

from sixdof_msgs.msg import RobotModelGripper, RobotModelGroupState


def gripper_msg(**changes) -> RobotModelGripper:
    """The fixture robot's gripper as get_robot_model serves it: TCP 0.1 m along link6's z, turned 90 deg about it."""
    msg = RobotModelGripper(
        group="gripper",
        end_effector="hand",
        tcp_frame="tcp",
        parent_link="link6",
        open=RobotModelGroupState(group="gripper", name="open", joint_names=["finger1_joint"], positions=[0.04]),
        closed=RobotModelGroupState(group="gripper", name="close", joint_names=["finger1_joint"], positions=[0.0]),
        max_opening=0.08,
        closed_width=0.0,
        finger_reach=0.015,
        palm_depth=0.05,
        pad_links=["finger1", "finger2"],
        closing_direction=Vector3(-1.0, 0.0, 0.0),
        approach_direction=Vector3(0.0, 0.0, 1.0),
    )
    msg.tcp.position.z = 0.1
    msg.tcp.orientation.z, msg.tcp.orientation.w = math.sin(math.pi / 4), math.cos(math.pi / 4)
    for key, value in changes.items():
        setattr(msg, key, value)
    return msg


@pytest.fixture()
def with_gripper(srdf):
    return dataclasses.replace(srdf, grippers=(gripper_from_msg(gripper_msg()),))


def test_the_gripper_message_is_read_as_it_is(with_gripper):
    g = with_gripper.grippers[0]
    assert (g.group, g.end_effector, g.tcp_frame, g.parent_link) == ("gripper", "hand", "tcp", "link6")
    assert (g.open_state, g.open_positions) == ("open", {"finger1_joint": 0.04})
    assert (g.closed_state, g.closed_positions) == ("close", {"finger1_joint": 0.0})
    assert (g.max_opening, g.finger_reach, g.palm_depth, g.pad_links) == (0.08, 0.015, 0.05, ("finger1", "finger2"))
    np.testing.assert_allclose(g.tcp, homogeneous([0.0, 0.0, 0.1], matrix_from_rpy(0.0, 0.0, math.pi / 2)), atol=1e-12)
    np.testing.assert_allclose(g.closing_direction, [-1.0, 0.0, 0.0])


def test_the_gripper_is_the_one_move_group_serves(srdf, with_gripper):
    assert find_gripper(with_gripper, None)[0].group == "gripper"
    assert find_gripper(with_gripper, "gripper")[0].group == "gripper"
    none, why = find_gripper(srdf, None)
    assert none is None and "has no gripper: move_group has no grasping information" in why
    none, why = find_gripper(with_gripper, "both")
    assert none is None and "group 'both' is no gripper" in why and "only for ['gripper']" in why
    none, why = find_gripper(with_gripper, "claw")
    assert none is None and "its SRDF has no group 'claw'" in why


def test_the_arm_group_is_the_one_the_gripper_ends(srdf, with_gripper):
    # The end effector 'hand' has no parent group: the chain group whose tip is its parent link.
    assert arm_group(with_gripper, with_gripper.grippers[0]) == "arm"
    assert arm_group(srdf, None) == "arm"  # without a gripper: the first chain group
    with pytest.raises(SixdofCommanderError, match="no chain group"):
        arm_group(dataclasses.replace(srdf, groups={}), None)


def test_home_is_the_arm_groups_first_state(srdf):
    assert home_state(srdf, "arm") == "home pose"
    with pytest.raises(SixdofCommanderError, match="no named state of group 'both'"):
        home_state(srdf, "both")


def test_links_joined_by_fixed_joints_either_way(urdf):
    np.testing.assert_allclose(link_in_link(urdf, "link6", "tcp")[:3, 3], [0.0, 0.0, 0.1])
    np.testing.assert_allclose(link_in_link(urdf, "tcp", "link6")[:3, 3], [0.0, 0.0, -0.1])
    np.testing.assert_allclose(link_in_link(urdf, "link6", "link6"), np.eye(4))
    with pytest.raises(SixdofCommanderError, match="separated by the moving joint 'finger1_joint'"):
        link_in_link(urdf, "link6", "finger1")
    with pytest.raises(SixdofCommanderError, match="not joined by fixed joints"):
        link_in_link(urdf, "finger1", "finger2")


def test_grasp_spec_has_the_closing_axis_in_the_tcp_frame(with_gripper):
    spec = grasp_spec(with_gripper.grippers[0], np.eye(4))
    # Closing along link6's -x, the TCP turned 90 deg about z: along the TCP's y axis.
    np.testing.assert_allclose(spec.finger_axis, [0.0, 1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(spec.tcp_in_tip[:3, 3], [0.0, 0.0, 0.1], atol=1e-12)
    assert (spec.max_width, spec.reach, spec.palm_depth) == (0.08, 0.015, 0.05)
    # A tip link below the gripper's parent (e.g. a flange 0.02 m out): the TCP is 0.08 beyond it.
    spec = grasp_spec(with_gripper.grippers[0], homogeneous([0.0, 0.0, -0.02], np.eye(3)))
    np.testing.assert_allclose(spec.tcp_in_tip[:3, 3], [0.0, 0.0, 0.08], atol=1e-12)
