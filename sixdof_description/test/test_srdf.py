"""The SRDF: well-formed, consistent with the URDF, named states within limits and where they were meant to be."""

import math

import pytest
import trimesh

import sixdof_core
from sixdof_description import cad
from sixdof_setup_assistant.generator import config_files

ARM = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
ARM_STATES = ["home pose", "pick pose", "after pick pose", "place pose", "after place pose"]


def test_groups_end_effector_virtual_joint(srdf):
    assert srdf.get("name") == "sixdof"
    groups = {g.get("name"): g for g in srdf.findall("group")}
    assert set(groups) == {"arm", "gripper"}
    chain = groups["arm"].find("chain")
    assert (chain.get("base_link"), chain.get("tip_link")) == ("base_link", "link6")
    assert [j.get("name") for j in groups["gripper"].findall("joint")] == ["finger1_joint", "finger2_joint"]
    ee = srdf.findall("end_effector")
    assert len(ee) == 1
    assert (ee[0].get("name"), ee[0].get("parent_link"), ee[0].get("group")) == ("hand", "link6", "gripper")
    vj = srdf.find("virtual_joint")
    assert (vj.get("type"), vj.get("parent_frame"), vj.get("child_link")) == ("fixed", "world", "base_link")


def test_every_named_link_and_joint_exists(srdf, robot):
    links, joints = set(robot.link_map), {j.name for j in robot.joints}
    for e in srdf.iter():
        for attr in ("link1", "link2", "parent_link", "child_link", "base_link", "tip_link"):
            if e.get(attr) is not None:
                assert e.get(attr) in links, f"<{e.tag} {attr}={e.get(attr)}>: no such link"
        if e.tag == "joint":
            assert e.get("name") in joints, f"joint {e.get('name')} is not in the URDF"
        if e.tag == "disable_collisions":
            assert e.get("reason") in ("Adjacent", "Default", "Always", "Never", "User")


def test_adjacent_pairs_are_the_joined_links(srdf, robot):
    adjacent = {frozenset((d.get("link1"), d.get("link2")))
                for d in srdf.findall("disable_collisions") if d.get("reason") == "Adjacent"}
    with_geometry = {name for name, link in robot.link_map.items() if link.collision is not None}
    expected = {frozenset((j.parent, j.child)) for j in robot.joints
                if j.parent in with_geometry and j.child in with_geometry}
    assert adjacent == expected


def _states(srdf, group):
    return {s.get("name"): {j.get("name"): float(j.get("value")) for j in s.findall("joint")}
            for s in srdf.findall("group_state") if s.get("group") == group}


def test_named_states_are_within_limits(srdf, robot):
    limits = {j.name: (j.limit.lower, j.limit.upper) for j in robot.joints if j.limit is not None}
    arm = _states(srdf, "arm")
    assert list(arm) == ARM_STATES
    for name, values in arm.items():
        assert list(values) == ARM
        for joint, v in values.items():
            lo, hi = limits[joint]
            assert lo <= v <= hi, f"{name}: {joint}={v} outside [{lo}, {hi}]"
    # finger2_joint mimics finger1_joint: the states list the actuated joint only.
    assert _states(srdf, "gripper") == {"open": {"finger1_joint": 0.04}, "close": {"finger1_joint": 0.0}}


def _state(core_model, q_arm, finger=0.0) -> sixdof_core.RobotState:
    state = sixdof_core.RobotState(core_model)
    state.set_group_positions("arm", q_arm)
    state.set_joint_position("finger1_joint", finger)
    return state


@pytest.mark.parametrize("state", ARM_STATES)
def test_named_state_reaches_its_design_pose(srdf, core_model, design, state):
    spec = design["named_states"][state]
    q = [_states(srdf, "arm")[state][j] for j in ARM]
    target = sixdof_core.pose_from_xyz_rpy(*spec["xyz"], *[math.radians(a) for a in spec["rpy_deg"]])
    perr, rerr = sixdof_core.pose_error(_state(core_model, q).link_pose(spec["frame"]), target)
    assert perr < 1e-5 and rerr < 1e-5


def test_pick_and_place_poses_point_down_over_their_places(srdf, core_model):
    states = _states(srdf, "arm")
    tcp = {name: _state(core_model, [states[name][j] for j in ARM]).link_pose("tcp") for name in ARM_STATES}
    for name in ARM_STATES[1:]:
        assert tcp[name][2, 2] == pytest.approx(-1.0, abs=1e-6), f"{name}: tool not pointing down"
    cube_top = 0.04
    assert tcp["pick pose"][2, 3] - 0.02 == pytest.approx(0.06, abs=1e-6)
    assert tcp["pick pose"][2, 3] > cube_top
    assert tuple(tcp["pick pose"][:2, 3]) == pytest.approx((0.40, -0.15), abs=1e-6)
    assert tuple(tcp["place pose"][:2, 3]) == pytest.approx((0.40, 0.20), abs=1e-6)
    assert tcp["after pick pose"][2, 3] - tcp["pick pose"][2, 3] == pytest.approx(0.15, abs=1e-6)
    assert tcp["after place pose"][2, 3] > tcp["place pose"][2, 3]


def test_regeneration_keeps_hand_written_entries(pkg):
    def regenerate(previous):
        files = config_files(str(pkg / "urdf" / "sixdof.urdf"), str(pkg / "config" / "setup_answers.yaml"), previous)
        return files["config/sixdof.srdf"]

    base = (pkg / "config" / "sixdof.srdf").read_text(encoding="utf-8")
    hand_written = base.replace(
        "</robot>",
        '  <group_state name="wave" group="arm"><joint name="joint1" value="0.5"/></group_state>\n'
        '  <disable_collisions link1="link1" link2="link4" reason="User"/>\n'
        '  <disable_collisions link1="base_link" link2="link6" reason="Adjacent"/>\n</robot>')
    regenerated = regenerate(hand_written)
    assert 'name="wave"' in regenerated
    assert 'link1="link1" link2="link4" reason="User"' in regenerated
    # The collision matrix is always recomputed, generated states are not duplicated.
    assert 'link1="base_link" link2="link6" reason="Adjacent"' not in regenerated
    assert regenerated.count('name="home pose"') == 1
    assert regenerate(regenerated) == regenerated
    assert regenerate(base) == base


def _link_poses(core_model, q_arm, finger):
    """Every link's 4x4 pose in base_link at arm joints q_arm and finger opening `finger`."""
    return _state(core_model, q_arm, finger).link_poses()


@pytest.mark.parametrize("state", ARM_STATES)
def test_named_states_keep_the_robot_above_the_table(pkg, srdf, robot, core_model, state):
    """Collision hulls of all moving links stay above z = 0; at 'pick pose' the open fingers clear the cube."""
    q = [_states(srdf, "arm")[state][j] for j in ARM]
    lowest = {}
    for link, pose in _link_poses(core_model, q, 0.04).items():
        if link == "base_link" or robot.link_map[link].collision is None:
            continue
        hull = trimesh.load(pkg / "meshes" / "collision" / f"{link}.stl")
        points = hull.vertices @ pose[:3, :3].T + pose[:3, 3]
        lowest[link] = points[:, 2].min()
    assert min(lowest.values()) > 0.0, lowest
    if state == "pick pose":
        cube_top = 0.04
        assert min(lowest["finger1"], lowest["finger2"]) > cube_top


def _placed_hulls(pkg, robot, core_model, q_arm, finger):
    hulls = {}
    for link, pose in _link_poses(core_model, q_arm, finger).items():
        if robot.link_map[link].collision is None:
            continue
        hulls[link] = trimesh.load(pkg / "meshes" / "collision" / f"{link}.stl")
        hulls[link].apply_transform(pose)
    return hulls


@pytest.mark.parametrize("state", ARM_STATES)
@pytest.mark.parametrize("gripper", ["open", "close"])
def test_named_states_are_free_of_self_collision(pkg, srdf, robot, core_model, state, gripper):
    """Collision hulls of links not allowed to touch do not overlap (manifold intersection volume)."""
    allowed = {frozenset((d.get("link1"), d.get("link2"))) for d in srdf.findall("disable_collisions")}
    q = [_states(srdf, "arm")[state][j] for j in ARM]
    finger = _states(srdf, "gripper")[gripper]["finger1_joint"]
    hulls = _placed_hulls(pkg, robot, core_model, q, finger)
    names = sorted(hulls)
    overlaps = []
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if frozenset((a, b)) in allowed:
                continue
            volume = (cad.to_manifold(hulls[a]) ^ cad.to_manifold(hulls[b])).volume()
            if volume > 1e-9:
                overlaps.append((a, b, volume))
    assert not overlaps
