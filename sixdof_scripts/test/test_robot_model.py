"""The commander's robot model on the fixture robot (move_group's model of it, core_model): groups, joint order,
limits, named states, end effectors, touch links."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from core_model import load_model
from sixdof_commander import SixdofCommanderError
from sixdof_commander.planning_scene import default_touch_links
from sixdof_commander.robot_model import resolve_group

REPO_URDF = Path(__file__).resolve().parents[2] / "sixdof_description" / "urdf" / "sixdof.urdf"


def test_arm_group_from_chain(arm):
    assert arm.joint_names == [f"joint{i}" for i in range(1, 7)]
    assert arm.tip_link == "link6"
    assert arm.end_effector_link == "link6"
    assert arm.end_effector_group == "gripper"
    assert arm.links == tuple(f"link{i}" for i in range(1, 7))


def test_limits_from_urdf(arm):
    limits = {j.name: (j.lower, j.upper) for j in arm.joints}
    assert limits["joint2"] == (-1.92, 1.92)
    assert limits["joint3"] == (-2.6, 2.6)
    assert limits["joint6"] == (-6.28319, 6.28319)


def test_gripper_group_moves_one_joint_the_other_mimics(urdf, srdf):
    gripper = resolve_group(urdf, srdf, "gripper")
    assert gripper.joint_names == ["finger1_joint"]
    assert gripper.links == ("finger1", "finger2")
    assert gripper.named_states == {
        "open": {"finger1_joint": 0.04, "finger2_joint": 0.04},
        "close": {"finger1_joint": 0.0},
    }
    assert [j.name for j in gripper.all_joints] == ["finger1_joint", "finger2_joint"]


def test_subgroups_are_merged(urdf, srdf):
    both = resolve_group(urdf, srdf, "both")
    assert both.joint_names == [f"joint{i}" for i in range(1, 7)] + ["finger1_joint"]


def test_named_states_per_group(srdf):
    assert sorted(srdf.group_states["arm"]) == ["home pose", "pick pose"]
    assert srdf.group_states["arm"]["home pose"]["joint5"] == 1.5708
    assert srdf.end_effectors[0].name == "hand" and srdf.end_effectors[0].parent_link == "link6"


def test_fixed_transform_link6_to_tcp(urdf):
    transform = urdf.fixed_transform("link6", "tcp")
    np.testing.assert_allclose(transform[:3, 3], [0.0, 0.0, 0.1])
    np.testing.assert_allclose(transform[:3, :3], np.eye(3))
    with pytest.raises(SixdofCommanderError, match="moving joint 'joint6'"):
        urdf.fixed_transform("link5", "tcp")


def test_default_touch_links_are_the_hand(urdf, srdf):
    assert default_touch_links(urdf, srdf, "link6") == ["link6", "palm", "tcp", "finger1", "finger2"]
    assert default_touch_links(urdf, srdf, "link3") == ["link3"]
    with pytest.raises(SixdofCommanderError, match="link 'hand' is not a link"):
        default_touch_links(urdf, srdf, "hand")


def test_unknown_group_is_rejected_naming_the_known_ones(urdf, srdf):
    with pytest.raises(SixdofCommanderError, match=r"no group 'manipulator'; groups: \['arm', 'both', 'gripper'\]"):
        resolve_group(urdf, srdf, "manipulator")


def test_a_state_naming_joints_outside_its_group_is_rejected(urdf, srdf):
    # The core refuses such an SRDF when it reads it; the commander checks the model it is given as well.
    bad = dataclasses.replace(srdf, group_states={"gripper": {"s": {"joint2": 0.0}}})
    with pytest.raises(SixdofCommanderError, match=r"state 's' of group 'gripper' names joints \['joint2'\]"):
        resolve_group(urdf, bad, "gripper")


def test_repository_urdf_has_the_design_joints():
    urdf, _ = load_model(REPO_URDF.read_text())
    assert urdf.root_link == "base_link"
    chain = [j.name for j in urdf.chain("base_link", "link6")]
    assert chain == [f"joint{i}" for i in range(1, 7)]
    assert (urdf.joints["joint2"].lower, urdf.joints["joint2"].upper) == (-1.92, 1.92)
    assert urdf.joints["joint6"].upper == pytest.approx(2 * math.pi, abs=1e-4)
    assert urdf.joints["finger2_joint"].mimic == "finger1_joint"
    # The grasp centre is rigidly on link6's z axis (design.md).
    tcp = urdf.fixed_transform("link6", "tcp")
    assert tcp[0, 3] == pytest.approx(0.0) and tcp[1, 3] == pytest.approx(0.0) and tcp[2, 3] > 0.0
