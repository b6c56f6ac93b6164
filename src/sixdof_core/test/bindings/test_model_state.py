"""RobotModel and RobotState through the bindings: loading, lookups, joints by group and name, FK, Jacobians,
bounds, random states, and bad input raising ValueError with the core's message."""

from __future__ import annotations

import copy

import numpy as np
import pytest
from conftest import DATA, DESCRIPTION

import sixdof_core


def test_model_from_strings_equals_model_from_files(arm):
    urdf = (DESCRIPTION / "urdf" / "sixdof.urdf").read_text(encoding="utf-8")
    srdf = (DESCRIPTION / "config" / "sixdof.srdf").read_text(encoding="utf-8")
    model = sixdof_core.RobotModel(urdf, srdf, package_dirs={"sixdof_description": str(DESCRIPTION)})
    assert model.name == arm.name == "sixdof"
    assert model.link_names == arm.link_names and model.joint_names == arm.joint_names
    assert model.variable_names == ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "finger1_joint"]
    assert model.group_names == ["arm", "gripper"]
    assert model.group("arm").chain_tip == "link6" and model.group("arm").is_chain
    assert [s.name for s in model.group_states if s.group == "arm"][0] == "home pose"
    assert model.end_effectors[0].parent_link == "link6"
    assert any(p.reason == "Adjacent" for p in model.disabled_collision_pairs)


def test_relative_package_directories(arm, monkeypatch):
    monkeypatch.chdir(DESCRIPTION.parent)
    model = sixdof_core.RobotModel.from_files("sixdof_description/urdf/sixdof.urdf",
                                              package_dirs={"sixdof_description": "sixdof_description"})
    assert model.link_names == arm.link_names


def test_joints_links_and_shapes(arm, joint_kinds):
    joint6 = arm.joint("joint6")
    assert joint6.type == sixdof_core.JointType.REVOLUTE and joint6.is_multi_turn and joint6.is_active
    np.testing.assert_allclose(joint6.origin[:3, 3], [0.08, 0.0, 0.0])
    finger2 = arm.joint("finger2_joint")
    assert finger2.mimic.joint == "finger1_joint" and finger2.variable_index == -1
    link = arm.link("link3")
    assert link.inertial.mass > 0 and link.inertial.inertia.shape == (3, 3)
    assert link.collision_shapes[0].shape.type == sixdof_core.ShapeType.MESH
    assert link.collision_shapes[0].shape.mesh_path.endswith("link3.stl")
    spin = joint_kinds.joint("spin")
    assert spin.type == sixdof_core.JointType.CONTINUOUS and not spin.limits.bounded
    assert (spin.limits.lower, spin.limits.upper) == pytest.approx((-np.pi, np.pi))
    # A model without SRDF has no semantics.
    bare = sixdof_core.RobotModel((DATA / "joint_kinds.urdf").read_text(encoding="utf-8"))
    assert bare.groups == [] and bare.variable_count == joint_kinds.variable_count


def test_bad_input_names_the_problem(arm):
    with pytest.raises(sixdof_core.RobotModelError, match="not well-formed|parse|XML|URDF"):
        sixdof_core.RobotModel("<robot name='x'><link name='a'>")
    with pytest.raises(sixdof_core.RobotModelError, match="nope.srdf"):
        sixdof_core.RobotModel.from_files(str(DESCRIPTION / "urdf" / "sixdof.urdf"), "/nope.srdf")
    with pytest.raises(sixdof_core.RobotModelError, match="sixdof_description"):
        sixdof_core.RobotModel.from_files(str(DESCRIPTION / "urdf" / "sixdof.urdf"), search_roots=[])
    with pytest.raises(ValueError, match="unknown group 'hand'.*'arm', 'gripper'"):
        arm.group("hand")
    with pytest.raises(ValueError, match="unknown link 'nope'"):
        arm.link("nope")
    state = sixdof_core.RobotState(arm)
    with pytest.raises(ValueError, match="group 'arm' has 6 variables, got 2"):
        state.set_group_positions("arm", [0.0, 1.0])
    with pytest.raises(ValueError, match="no named state 'wave'.*'home pose'"):
        state.set_to_named_state("arm", "wave")
    with pytest.raises(ValueError, match="'finger2_joint' is fixed or a mimic"):
        state.set_joint_positions({"joint1": 0.3, "finger2_joint": 0.01})
    assert state.joint_position("joint1") == 0.0  # nothing was set
    with pytest.raises(ValueError, match="non-finite"):
        state.positions = np.full(arm.variable_count, np.nan)


def test_joints_by_group_and_name_and_forward_kinematics(arm):
    state = sixdof_core.RobotState(arm)
    q = np.array([0.3, -0.4, 0.9, 1.2, -0.6, 2.0])
    state.set_group_positions("arm", q)
    state.set_joint_positions({"finger1_joint": 0.02})
    np.testing.assert_allclose(state.group_positions("arm"), q)
    assert state.joint_position("finger2_joint") == pytest.approx(0.02)  # the mimic joint follows
    assert list(state.joint_positions) == arm.variable_names
    chain = sixdof_core.KinematicChain.for_group(arm, "arm")
    np.testing.assert_allclose(state.link_pose("link6"), chain.forward(q), atol=1e-12)
    poses = state.link_poses()
    assert list(poses) == arm.link_names
    np.testing.assert_allclose(poses["tcp"], state.link_pose("tcp"))
    state.set_to_named_state("arm", "home pose")
    home = next(s for s in arm.group_states if s.name == "home pose")
    assert state.joint_position("joint2") == pytest.approx(home.values["joint2"])


def test_jacobian_of_a_point_matches_finite_differences(arm):
    state = sixdof_core.RobotState(arm)
    q = np.array([0.1, 0.4, 0.6, -0.7, 0.8, 0.3])
    state.set_group_positions("arm", q)
    point = np.array([0.01, 0.0, 0.05])
    jacobian = state.jacobian("arm", "tcp", point)
    assert jacobian.shape == (6, 6)
    np.testing.assert_allclose(state.jacobian("arm"), sixdof_core.KinematicChain.for_group(arm, "arm").jacobian(q),
                               atol=1e-12)
    base = state.link_pose("tcp") @ np.append(point, 1.0)
    for j in range(6):
        moved = state.copy()
        dq = q.copy()
        dq[j] += 1e-7
        moved.set_group_positions("arm", dq)
        velocity = (moved.link_pose("tcp") @ np.append(point, 1.0) - base)[:3] / 1e-7
        np.testing.assert_allclose(jacobian[:3, j], velocity, atol=1e-5)


def test_bounds_random_states_and_copies(arm, joint_kinds):
    state = sixdof_core.RobotState(arm)
    state.set_joint_position("joint2", 2.5)
    assert not state.satisfies_bounds()
    assert state.satisfies_bounds(tolerance=1.0)
    spun = sixdof_core.RobotState(joint_kinds)
    spun.set_joint_position("spin", 10.0)  # continuous: never out of bounds
    assert spun.satisfies_bounds()
    first, second = sixdof_core.StateSampler(arm, 3), sixdof_core.StateSampler(arm, 3)
    samples = [first.sample() for _ in range(20)]
    np.testing.assert_array_equal(samples[0], second.sample())
    for sample in samples:
        state.positions = sample
        assert state.satisfies_bounds()
    state.set_to_default_positions()
    state.set_to_random_positions(first, "arm")
    assert state.joint_position("finger1_joint") == arm.default_positions()[6]
    duplicate = copy.deepcopy(state)
    duplicate.set_joint_position("joint1", 1.0)
    assert state.joint_position("joint1") != 1.0
