"""The generated URDF: parses, keeps docs/design.md's kinematics, has valid and mesh-consistent inertias."""

import math
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import trimesh

import sixdof_core
from sixdof_description.urdf_writer import GRASP_FIX_BLOCK

PI = math.pi
# docs/design.md's joint table: origin xyz, rpy, axis, limits.
CONTRACT = {
    "joint1": ("base_link", "link1", (0, 0, 0.10), (0, 0, 0), (0, 0, 1), (-PI, PI)),
    "joint2": ("link1", "link2", (0, 0, 0.20), (0, 0, 0), (0, 1, 0), (-1.92, 1.92)),
    "joint3": ("link2", "link3", (0, 0, 0.30), (0, 0, 0), (0, 1, 0), (-2.6, 2.6)),
    "joint4": ("link3", "link4", (0.12, 0, 0), (0, 0, 0), (1, 0, 0), (-PI, PI)),
    "joint5": ("link4", "link5", (0.18, 0, 0), (0, 0, 0), (0, 1, 0), (-2.1, 2.1)),
    "joint6": ("link5", "link6", (0.08, 0, 0), (0, PI / 2, 0), (0, 0, 1), (-2 * PI, 2 * PI)),
}
LINKS = ["base_link", "link1", "link2", "link3", "link4", "link5", "link6", "palm", "finger1", "finger2"]
# docs/design.md: the paper's poses of link6 in base_link (rpy fixed axes, degrees). This module is the one place
# that asserts them: both reachable, the SRDF's home pose at the first.
PAPER_POSES = {
    "home": ((0.366, 0.0, 0.286), (-180.0, 0.688, 179.995)),
    "target": ((-0.568, 0.058, 0.396), (-133.151, 35.219, 1.048)),
}


def test_check_urdf_is_clean(pkg):
    tool = shutil.which("check_urdf")
    assert tool, "check_urdf (liburdfdom-tools) is not installed"
    run = subprocess.run([tool, str(pkg / "urdf" / "sixdof.urdf")], capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "Error" not in run.stdout + run.stderr
    assert "root Link: base_link has 1 child(ren)" in run.stdout


def test_arm_joints_follow_the_design_contract(robot):
    joints = {j.name: j for j in robot.joints}
    revolute = [j.name for j in robot.joints if j.type == "revolute"]
    assert revolute == list(CONTRACT)
    for name, (parent, child, xyz, rpy, axis, limits) in CONTRACT.items():
        j = joints[name]
        assert (j.parent, j.child) == (parent, child)
        np.testing.assert_allclose(j.origin.xyz, xyz, atol=1e-9)
        np.testing.assert_allclose(j.origin.rpy, rpy, atol=1e-8)
        np.testing.assert_allclose(j.axis, axis, atol=1e-12)
        assert j.limit.lower == pytest.approx(limits[0], abs=1e-8)
        assert j.limit.upper == pytest.approx(limits[1], abs=1e-8)
        assert j.limit.velocity > 0 and j.limit.effort > 0
        assert j.dynamics.damping > 0 and j.dynamics.friction >= 0


def test_zero_pose_matches_the_contract(core_model):
    link6 = sixdof_core.RobotState(core_model).link_pose("link6")  # every joint at zero
    np.testing.assert_allclose(link6[:3, 3], [0.38, 0.0, 0.60], atol=1e-12)
    np.testing.assert_allclose(link6[:3, 2], [1, 0, 0], atol=1e-12)  # z axis
    np.testing.assert_allclose(link6[:3, 0], [0, 0, -1], atol=1e-12)  # x axis


def test_gripper_joints(robot):
    joints = {j.name: j for j in robot.joints}
    assert joints["palm_joint"].type == "fixed" and joints["palm_joint"].parent == "link6"
    f1, f2 = joints["finger1_joint"], joints["finger2_joint"]
    assert (f1.type, f1.parent, f1.child) == ("prismatic", "palm", "finger1")
    assert (f2.type, f2.parent, f2.child) == ("prismatic", "palm", "finger2")
    np.testing.assert_allclose(f1.axis, [0, 1, 0])
    np.testing.assert_allclose(f2.axis, [0, -1, 0])
    for j in (f1, f2):
        assert (j.limit.lower, j.limit.upper) == (0.0, 0.04)
    assert f2.mimic is not None and f2.mimic.joint == "finger1_joint"
    assert (f2.mimic.multiplier or 1.0) == 1.0 and (f2.mimic.offset or 0.0) == 0.0
    tcp = joints["tcp_joint"]
    assert (tcp.type, tcp.parent, tcp.child) == ("fixed", "link6", "tcp")
    assert tcp.origin.xyz[0] == 0.0 and tcp.origin.xyz[1] == 0.0 and tcp.origin.xyz[2] > 0.0


def test_tcp_is_centred_between_the_pads(pkg, robot):
    """The finger's pad face is at y = 0 of its frame, and the tcp sits mid-height of the pads."""
    joints = {j.name: j for j in robot.joints}
    finger1 = trimesh.load(pkg / "meshes" / "visual" / "finger1.stl")
    assert finger1.bounds[0][1] == pytest.approx(0.0, abs=1e-6)
    face = finger1.vertices[finger1.vertices[:, 1] < 1e-4]
    pad_mid_z = (face[:, 2].min() + face[:, 2].max()) / 2.0
    finger_z = joints["palm_joint"].origin.xyz[2] + joints["finger1_joint"].origin.xyz[2]
    assert joints["tcp_joint"].origin.xyz[2] == pytest.approx(finger_z + pad_mid_z, abs=2e-4)
    # 3-6 cm objects fit between pads that open to 2 x 0.04 m.
    pad_length = face[:, 2].max() - face[:, 2].min()
    assert 0.015 < pad_length < 0.04


def test_the_root_link_has_no_inertia(robot):
    # KDL (robot_state_publisher, kdl_parser) cannot use an inertia on the root and warns about it.
    assert robot.get_root() == "base_link"
    assert robot.link_map["base_link"].inertial is None


@pytest.mark.parametrize("name", LINKS[1:])
def test_inertia_is_physically_valid(robot, name):
    inertial = robot.link_map[name].inertial
    assert inertial.mass > 0.0
    i = inertial.inertia
    tensor = np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])
    principal = np.linalg.eigvalsh(tensor)
    assert principal.min() > 0.0, f"{name}: inertia not positive definite {principal}"
    a, b, c = principal
    tol = 1e-12
    assert a + b >= c - tol and b + c >= a - tol and a + c >= b - tol, f"{name}: triangle inequality {principal}"


@pytest.mark.parametrize("name", LINKS[1:])
def test_inertia_matches_the_mesh(pkg, robot, design, name):
    mesh = trimesh.load(pkg / "meshes" / "visual" / f"{name}.stl")
    assert mesh.is_watertight, f"{name}: visual mesh is not closed"
    mesh.density = design["density"]
    inertial = robot.link_map[name].inertial
    assert inertial.mass == pytest.approx(mesh.mass, rel=1e-4)
    np.testing.assert_allclose(inertial.origin.xyz, mesh.center_mass, atol=1e-6)
    np.testing.assert_allclose(inertial.origin.rpy, [0, 0, 0])
    i = inertial.inertia
    tensor = np.array([[i.ixx, i.ixy, i.ixz], [i.ixy, i.iyy, i.iyz], [i.ixz, i.iyz, i.izz]])
    scale = np.abs(mesh.moment_inertia).max()
    np.testing.assert_allclose(tensor, mesh.moment_inertia, atol=1e-4 * scale)


@pytest.mark.parametrize("name", LINKS)
def test_meshes_exist_and_collision_is_a_small_convex_hull(pkg, robot, name):
    link = robot.link_map[name]
    prefix = "package://sixdof_description/"
    assert link.visual.geometry.filename == f"{prefix}meshes/visual/{name}.stl"
    assert link.collision.geometry.filename == f"{prefix}meshes/collision/{name}.stl"
    hull = trimesh.load(pkg / "meshes" / "collision" / f"{name}.stl")
    visual = trimesh.load(pkg / "meshes" / "visual" / f"{name}.stl")
    assert hull.is_convex and hull.is_watertight
    assert len(hull.faces) <= 200
    # The hull encloses the visual solid (up to the coarse tessellation of round parts).
    assert hull.volume >= 0.9 * visual.volume
    assert link.visual.material is not None and link.visual.material.name


def test_materials_have_colours(robot):
    for material in robot.materials:
        assert material.color is not None and len(material.color.rgba) == 4


def test_grasp_fix_block_and_friction(pkg):
    text = (pkg / "urdf" / "sixdof.urdf").read_text(encoding="utf-8")
    root = ET.fromstring(text)
    plugins = root.findall("gazebo/plugin[@name='gazebo_grasp_fix']")
    assert len(plugins) == 1
    expected = ET.fromstring(GRASP_FIX_BLOCK).find("plugin")

    def canon(e):
        return (e.tag, dict(e.attrib), (e.text or "").strip(), [canon(c) for c in e])

    assert canon(plugins[0]) == canon(expected)
    arm = plugins[0].find("arm")
    assert arm.findtext("palm_link") == "link6"
    assert [g.text for g in arm.findall("gripper_link")] == ["finger1", "finger2"]
    assert plugins[0].findtext("release_tolerance") == "0.005"
    for link in LINKS:
        ref = root.find(f"gazebo[@reference='{link}']")
        assert ref is not None, f"no friction for {link}"
        assert float(ref.findtext("mu1")) > 0 and float(ref.findtext("mu2")) > 0
    assert float(root.find("gazebo[@reference='finger1']").findtext("mu1")) >= 1.0


@pytest.mark.parametrize("pose", sorted(PAPER_POSES))
def test_paper_pose_is_reachable(core_model, pose):
    # The core's numeric IK from the middle of the joint ranges: another algorithm than the generator's closed form.
    ik = sixdof_core.create_ik_solver("numeric", core_model, "arm")
    xyz, rpy_deg = PAPER_POSES[pose]
    target = sixdof_core.pose_from_xyz_rpy(*xyz, *[math.radians(a) for a in rpy_deg])
    result = ik.solve(target, sixdof_core.IkOptions(timeout=0.5, random_seed=11))
    assert result, f"{pose} pose unreachable: {result.message}"
    perr, rerr = sixdof_core.pose_error(ik.chain.forward(result.solution), target)
    assert perr < 1e-5 and rerr < 1e-5
    assert ik.chain.within_limits(result.solution)


def test_home_pose_state_is_the_paper_home_pose(core_model):
    state = sixdof_core.RobotState(core_model)
    state.set_to_named_state("arm", "home pose")
    xyz, rpy_deg = PAPER_POSES["home"]
    target = sixdof_core.pose_from_xyz_rpy(*xyz, *[math.radians(a) for a in rpy_deg])
    perr, rerr = sixdof_core.pose_error(state.link_pose("link6"), target)
    assert perr < 1e-3 and rerr < 1e-2


def test_the_core_reads_the_whole_robot(core_model):
    # Breadth first, siblings in document order: link6's children palm and tcp before palm's fingers.
    assert core_model.link_names == [*LINKS[:8], "tcp", *LINKS[8:]]
    assert core_model.variable_names == [*CONTRACT, "finger1_joint"]
    assert core_model.joint("finger2_joint").mimic.joint == "finger1_joint"
    assert sixdof_core.KinematicChain(core_model, "base_link", "tcp").dof == 6
    assert sixdof_core.KinematicChain(core_model, "base_link", "finger1").joint_names[-1] == "finger1_joint"
