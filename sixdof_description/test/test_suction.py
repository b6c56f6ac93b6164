"""The suction variant (design.yaml `tool: suction`): the committed urdf/sixdof_suction.urdf, config/suction/ and
meshes/*/cup.stl are what the generator produces; the cup, its inertia and TCP, the SRDF's group and end effector,
grasping.yaml's `suction`."""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import yaml
from urdf_parser_py import urdf

from sixdof_description import cad
from sixdof_description.generator import generate_files, generated_files

SUCTION_FILES = generated_files("suction")


@pytest.fixture(scope="module")
def generated(pkg):
    previous = (pkg / "config" / "suction" / "sixdof_suction.srdf").read_text(encoding="utf-8")
    return generate_files(pkg / "config" / "design.yaml", previous, "suction")


@pytest.fixture(scope="module")
def suction_robot(pkg) -> urdf.Robot:
    return urdf.Robot.from_xml_string((pkg / "urdf" / "sixdof_suction.urdf").read_text(encoding="utf-8"))


def test_the_generator_makes_every_suction_file(generated):
    assert sorted(generated) == sorted(SUCTION_FILES)


@pytest.mark.parametrize("rel", SUCTION_FILES)
def test_committed_suction_file_is_up_to_date(pkg, generated, rel):
    assert (pkg / rel).read_bytes() == generated[rel], f"{rel} is stale: run `make -C sixdof_description`"


def test_the_arm_is_the_two_finger_arms(pkg, generated):
    """Same links, meshes and joints up to link6: only the tool differs."""
    for rel in SUCTION_FILES:
        if rel.startswith("meshes/") and not rel.endswith("cup.stl"):
            assert generated[rel] == (pkg / rel).read_bytes()
    two_finger = urdf.Robot.from_xml_string((pkg / "urdf" / "sixdof.urdf").read_text(encoding="utf-8"))
    suction = urdf.Robot.from_xml_string(generated["urdf/sixdof_suction.urdf"].decode())
    for name in ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6"):
        assert suction.joint_map[name].origin.xyz == two_finger.joint_map[name].origin.xyz


def test_the_cup_is_a_short_cylinder_on_the_flange(design, suction_robot):
    """No moving joint after the arm; the cup on the flange with a cylinder's inertia; the tcp at its face."""
    cup = design["suction_cup"]
    flange = design["links"]["link6"]["flange_t"]
    moving = [j.name for j in suction_robot.joints if j.type != "fixed"]
    assert moving == [f"joint{i}" for i in range(1, 7)]
    joint = suction_robot.joint_map["cup_joint"]
    assert (joint.parent, joint.child) == ("link6", "cup") and joint.origin.xyz == pytest.approx([0, 0, flange])
    tcp = suction_robot.joint_map["tcp_joint"]
    assert (tcp.parent, tcp.child) == ("link6", "tcp")
    assert tcp.origin.xyz == pytest.approx([0, 0, flange + cup["length"]])
    # The inertia of a solid cylinder of the design's density (the fillet takes a little off).
    inertial = suction_robot.link_map["cup"].inertial
    r, h = cup["radius"], cup["length"]
    mass = design["density"] * math.pi * r * r * h
    assert inertial.mass == pytest.approx(mass, rel=0.03)
    assert inertial.origin.xyz == pytest.approx([0, 0, h / 2], abs=1e-4)
    izz = inertial.inertia.izz
    assert izz == pytest.approx(mass * r * r / 2, rel=0.05)
    assert inertial.inertia.ixx == pytest.approx(mass * (3 * r * r + h * h) / 12, rel=0.05)
    assert np.asarray(tcp.origin.rpy) == pytest.approx([0, 0, 0])  # the face is square to link6's z


def test_no_grasp_fix_block(pkg):
    """The simulator's cup comes from grasping.yaml's `suction`; the URDF has no plugin block."""
    root = ET.parse(pkg / "urdf" / "sixdof_suction.urdf").getroot()
    assert not [plugin.get("name") for plugin in root.iter("plugin")]


def test_the_config_names_the_cup(pkg, design):
    config = pkg / "config" / "suction"
    grasping = yaml.safe_load((config / "grasping.yaml").read_text())
    cup = design["suction_cup"]
    assert grasping["tcp"]["parent_link"] == "link6" and grasping["tcp"]["source"] == "link 'tcp'"
    assert grasping["tcp"]["xyz"] == pytest.approx([0, 0, design["links"]["link6"]["flange_t"] + cup["length"]])
    assert grasping["approach_direction"] == pytest.approx([0, 0, 1])
    assert grasping["suction"] == {"cup_link": "tcp", "max_payload": cup["max_payload"],
                                   "tilt_tolerance": cup["tilt_tolerance"], "contact_distance": cup["contact_distance"],
                                   "controller": "gripper_controller", "arm_name": "arm"}
    srdf = ET.parse(config / "sixdof_suction.srdf").getroot()
    group = next(g for g in srdf.findall("group") if g.get("name") == "gripper")
    assert [link.get("name") for link in group.findall("link")] == ["cup"]
    ee = srdf.find("end_effector")
    assert (ee.get("name"), ee.get("parent_link"), ee.get("group")) == ("hand", "link6", "gripper")
    states = {s.get("name") for s in srdf.findall("group_state")}
    assert states == set(design["named_states"])
    controllers = yaml.safe_load((config / "controllers.yaml").read_text())
    assert [c["name"] for c in controllers["controller_list"]] == ["arm_controller"]


def test_a_bad_tool_is_named(pkg, tmp_path):
    design = yaml.safe_load((pkg / "config" / "design.yaml").read_text())
    design["tool"] = "magnet"
    bad = tmp_path / "design.yaml"
    bad.write_text(yaml.safe_dump(design), encoding="utf-8")
    with pytest.raises(cad.DesignError, match="tool must be one of two_finger, suction, got 'magnet'"):
        generate_files(bad, None)
    design["tool"] = "suction"
    design["suction_cup"]["radius"] = 0.0
    bad.write_text(yaml.safe_dump(design), encoding="utf-8")
    with pytest.raises(cad.DesignError, match=r"suction_cup.radius must be positive"):
        generate_files(bad, None)

