"""Grippers without answers: the grasp frame, open/close and inertias the setup assistant infers for the fixture
robots of sixdof_test_robots (issue #21), and the answers keys that override them."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml
from conftest import FIXTURES, PACKAGE, ROBOTS, run, srdf

GRIPPERS = {
    "seven_dof_hand": (ROBOTS / "urdf" / "seven_dof_hand.urdf.xacro", ""),
    "six_r_adaptive": (ROBOTS / "urdf" / "six_r_adaptive.urdf.xacro", ""),
    "six_r_jaw": (ROBOTS / "urdf" / "six_r_adaptive.urdf.xacro", "gripper:=jaw"),
}
ADAPTIVE_LINKS = ["left_outer_knuckle", "right_outer_knuckle", "left_inner_knuckle", "right_inner_knuckle",
                  "left_inner_finger", "right_inner_finger"]

# The grasp frames the fixtures were built with (their URDF comments give the dimensions), in the arm's tip link:
# - seven_dof_hand: hand 4 cm beyond link7, turned 45 deg about z; pads 5.5 cm long from the palm face 5 cm into
#   the hand: midway at 0.04 + 0.05 + 0.0275.
# - six_r_adaptive: knuckles of 5.5 cm jointed 6 cm into the gripper, tilted -0.35 + 0.4 rad when half closed
#   (finger_joint 0.4), pads 4 cm long below them; the gripper's z is link_6's x (tool0).
# - six_r_jaw: jaws of 7.5 cm jointed 5 cm into the palm, in contact at their tips, -0.075 rad when half closed.
TCP = {
    "seven_dof_hand": ("link7", [0.0, 0.0, 0.04 + 0.05 + 0.0275], [0.0, 0.0, math.pi / 4]),
    "six_r_adaptive": ("link_6", [0.06 + 0.055 * math.cos(0.05) + 0.02, 0.0, 0.0], [0.0, math.pi / 2, 0.0]),
    "six_r_jaw": ("link_6", [0.05 + 0.075 * math.cos(0.075), 0.0, 0.0], [0.0, math.pi / 2, 0.0]),
}
# actuated finger joint, open, closed, opening (m)
STATES = {
    "seven_dof_hand": ("left_finger_joint", 0.04, 0.0, 0.08),
    "six_r_adaptive": ("finger_joint", 0.0, 0.8, 2 * (0.0239 + 0.055 * math.sin(0.35))),
    "six_r_jaw": ("left_jaw_joint", 0.3, -0.45, 0.08),
}


@pytest.fixture(scope="module")
def packages(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, str]]:
    """Each gripper robot's package (generated without answers) and the setup assistant's stderr."""
    out = tmp_path_factory.mktemp("grippers")
    made = {}
    for name, (urdf, xacro_args) in GRIPPERS.items():
        result = run("--urdf", urdf, "--package-out", out, "--name", f"{name}_config", "--density", "300",
                     "--xacro-args", xacro_args)
        assert result.returncode == 0, result.stderr
        made[name] = (out / f"{name}_config", result.stderr)
    return made


def grasping(package: Path) -> dict:
    return yaml.safe_load((package / "config/grasping.yaml").read_text())


def states(package: Path, robot: str) -> dict:
    root = srdf(next((package / "config").glob("*.srdf")))
    return {s.get("name"): {j.get("name"): float(j.get("value")) for j in s.findall("joint")}
            for s in root.findall("group_state") if s.get("group") == "gripper"}


@pytest.mark.parametrize("robot", list(GRIPPERS))
def test_the_grasp_frame_is_inferred_between_the_pads(packages: dict, robot: str) -> None:
    package, _ = packages[robot]
    data = grasping(package)
    parent, xyz, rpy = TCP[robot]
    assert data["tcp"]["source"] == "pads" and data["tcp"]["parent_link"] == parent
    assert data["tcp"]["xyz"] == pytest.approx(xyz, abs=1e-6)
    assert data["tcp"]["rpy"] == pytest.approx(rpy, abs=1e-6)
    # The URDF carries it as the link `tcp`, the rviz config shows its axes, the README gives it.
    urdf = ET.parse(next((package / "urdf").glob("*.urdf"))).getroot()
    joint = next(j for j in urdf.findall("joint") if j.find("child").get("link") == "tcp")
    assert joint.get("type") == "fixed" and joint.find("parent").get("link") == parent
    assert [float(v) for v in joint.find("origin").get("xyz").split()] == pytest.approx(xyz, abs=1e-6)
    rviz = yaml.safe_load((package / "config/motion_planning.rviz").read_text())
    axes = [d for d in rviz["Visualization Manager"]["Displays"] if d["Class"] == "rviz/Axes"]
    assert axes and axes[0]["Reference Frame"] == "tcp"
    readme = (package / "README.md").read_text()
    assert f"TCP: link `tcp` at xyz ({', '.join(f'{v:.4f}' for v in xyz)}) m" in readme
    assert f"in `{parent}`" in readme
    root = srdf(next((package / "config").glob("*.srdf")))
    assert root.find("end_effector").get("parent_link") == parent


@pytest.mark.parametrize("robot", list(GRIPPERS))
def test_open_and_close_come_from_the_pads_distance(packages: dict, robot: str) -> None:
    package, _ = packages[robot]
    joint, opened, closed, opening = STATES[robot]
    # Only the actuated joint: mimic joints follow it.
    assert states(package, robot) == {"open": {joint: opened}, "close": {joint: closed}}
    data = grasping(package)
    assert data["open"] == {"state": "open", "positions": {joint: opened}}
    assert data["closed"] == {"state": "close", "positions": {joint: closed}}
    assert data["max_opening"] == pytest.approx(opening, abs=1e-5)
    assert data["max_opening"] > 0.06  # 3-6 cm objects fit
    assert len(data["pad_links"]) == 2 and set(data["pad_links"]) <= set(data["grasp_fix"]["gripper_links"])
    assert data["closing_direction"] == pytest.approx([0.0, 1.0, 0.0] if robot != "seven_dof_hand"
                                                      else [-math.sqrt(0.5), math.sqrt(0.5), 0.0], abs=1e-6)
    assert data["grasp_fix"]["palm_link"] == TCP[robot][0]
    assert data["grasp_fix"]["forces_angle_tolerance"] == 120.0 and data["grasp_fix"]["max_grip_count"] == 10


def test_the_adaptive_gripper_generates_with_warnings_not_errors(packages: dict) -> None:
    package, stderr = packages["six_r_adaptive"]
    lines = stderr.strip().splitlines()
    assert all(line.startswith("setup_assistant: warning: ") for line in lines), stderr
    for link in ADAPTIVE_LINKS:
        assert any(f"link '{link}': no <inertial>: inertia computed from its collision geometry at 1000 kg/m^3" in line
                   for line in lines), link
    mimic = [line for line in lines if "mimics" in line]
    assert len(mimic) == 1 and "'left_inner_finger_joint' mimics 'finger_joint'" in mimic[0]
    assert "[0, 0.8757]" in mimic[0] and "[-0.8, 0]" in mimic[0]
    readme = (package / "README.md").read_text().split("## Warnings")[1]
    assert all(f"link '{link}'" in readme for link in ADAPTIVE_LINKS) and "left_inner_finger_joint" in readme


def test_computed_inertias_are_in_the_urdf_and_nothing_else_changes(packages: dict,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    package, _ = packages["six_r_adaptive"]
    text = (package / "urdf/six_r_adaptive.urdf").read_text()
    urdf = ET.fromstring(text)
    links = {link.get("name"): link for link in urdf.findall("link")}
    for name in ADAPTIVE_LINKS:
        inertial = links[name].find("inertial")
        assert inertial is not None, name
        mass = float(inertial.find("mass").get("value"))
        size = [float(v) for v in links[name].find("collision/geometry/box").get("size").split()]
        assert mass == pytest.approx(1000.0 * size[0] * size[1] * size[2], rel=1e-6)  # a box at 1000 kg/m^3
    # Take out what the setup assistant added: the expanded xacro is what remains.
    stripped = re.sub(r"\n *<!-- computed by sixdof setup_assistant[^\n]*\n *<inertial>.*?</inertial>", "", text,
                      flags=re.S)
    stripped = re.sub(r"  <link name=\"tcp\"/>\n  <joint name=\"tcp_joint\".*?</joint>\n", "", stripped, flags=re.S)
    monkeypatch.syspath_prepend(str(PACKAGE / "src"))
    from sixdof_setup_assistant.xacro_loader import load_description

    assert stripped == load_description(str(GRIPPERS["six_r_adaptive"][0]))


def test_robots_without_repairs_keep_their_urdf_and_print_no_warning(packages: dict) -> None:
    package, stderr = packages["seven_dof_hand"]
    assert stderr == ""
    assert "None." in (package / "README.md").read_text().split("## Warnings")[1]
    assert "computed by sixdof setup_assistant" not in (package / "urdf/seven_dof_hand.urdf").read_text()


def test_the_sixdof_arms_tcp_link_wins(tmp_path: Path) -> None:
    result = run("--urdf", FIXTURES["sixdof"], "--package-out", tmp_path, "--density", "100", check=True)
    assert result.stderr == ""
    package = tmp_path / "sixdof_sixdof_config"
    assert (package / "urdf/sixdof.urdf").read_text() == FIXTURES["sixdof"].read_text()
    data = grasping(package)
    assert data["tcp"]["source"] == "link 'tcp'" and data["tcp"]["parent_link"] == "link6"
    assert data["pad_links"] == ["finger2", "finger1"] and data["max_opening"] == pytest.approx(0.08)


def test_answers_override_the_grasp_geometry_and_density(tmp_path: Path) -> None:
    answers = tmp_path / "answers.yaml"
    answers.write_text(yaml.safe_dump({
        "default_density": 2000,
        "grasping": {"tcp": {"parent_link": "tool0", "xyz": [0.0, 0.0, 0.15], "rpy": [0.0, 0.0, 0.0]},
                     "pad_links": ["left_inner_finger", "right_inner_finger"], "max_opening": 0.07,
                     "grasp_fix": {"update_rate": 10, "gripper_links": ["left_inner_finger", "right_inner_finger"]}},
        "named_states": {"gripper": {"open": {"finger_joint": 0.1}}},
    }))
    result = run("--urdf", GRIPPERS["six_r_adaptive"][0], "--package-out", tmp_path, "--answers", answers,
                 "--density", "100")
    assert result.returncode == 0, result.stderr
    assert "at 2000 kg/m^3" in result.stderr
    package = tmp_path / "six_r_adaptive_sixdof_config"
    data = grasping(package)
    # tool0 is link_6 turned by pi/2 about y: 15 cm along tool0's z is 15 cm along link_6's x.
    assert data["tcp"]["source"] == "answers" and data["tcp"]["parent_link"] == "link_6"
    assert data["tcp"]["xyz"] == pytest.approx([0.15, 0.0, 0.0], abs=1e-9)
    assert data["tcp"]["rpy"] == pytest.approx([0.0, math.pi / 2, 0.0], abs=1e-9)
    assert data["pad_links"] == ["right_inner_finger", "left_inner_finger"] and data["max_opening"] == 0.07
    assert data["grasp_fix"]["update_rate"] == 10 and data["grasp_fix"]["max_grip_count"] == 10
    assert data["open"]["positions"] == {"finger_joint": 0.1} and data["closed"]["positions"] == {"finger_joint": 0.8}
    assert states(package, "six_r_adaptive") == {"open": {"finger_joint": 0.1}, "close": {"finger_joint": 0.8}}


@pytest.mark.parametrize("case", ["tcp_and_tcp_link", "mimic_joint_in_a_state", "unknown_pad", "bad_density",
                                  "bad_grasp_fix"])
def test_bad_gripper_answers_exit_2_naming_the_problem(tmp_path: Path, case: str) -> None:
    urdf = GRIPPERS["six_r_adaptive"][0]
    answers = {
        "tcp_and_tcp_link": {"grasping": {"tcp": {"parent_link": "link6", "xyz": [0, 0, 0.1], "rpy": [0, 0, 0]}}},
        "mimic_joint_in_a_state": {"named_states": {"gripper": {"open": {"left_inner_finger_joint": -0.1}}}},
        "unknown_pad": {"grasping": {"pad_links": ["left_inner_finger", "no_such_pad"]}},
        "bad_density": {"default_density": -5},
        "bad_grasp_fix": {"grasping": {"grasp_fix": {"grip_count_threshold": 12}}},
    }[case]
    if case == "tcp_and_tcp_link":
        urdf = FIXTURES["sixdof"]
    (tmp_path / "answers.yaml").write_text(yaml.safe_dump(answers))
    result = run("--urdf", urdf, "--package-out", tmp_path / "out", "--answers", tmp_path / "answers.yaml",
                 "--density", "100")
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    expected = {"tcp_and_tcp_link": "a link named 'tcp'", "mimic_joint_in_a_state": "mimics 'finger_joint'",
                "unknown_pad": "no_such_pad", "bad_density": "default_density",
                "bad_grasp_fix": "grip_count_threshold"}[case]
    assert expected in lines[0]
    assert not (tmp_path / "out").exists()


NO_GEOMETRY = """<?xml version="1.0"?>
<robot name="bare">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="spacer"/>
  <link name="shown"><visual><origin xyz="0 0 0.1"/><geometry><cylinder radius="0.02" length="0.2"/></geometry>
    </visual><inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="spacer"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="spacer"/><child link="shown"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""


def test_a_link_without_geometry_gets_the_default_and_visuals_stand_in_for_collisions(tmp_path: Path) -> None:
    urdf = tmp_path / "bare.urdf"
    urdf.write_text(NO_GEOMETRY)
    result = run("--urdf", urdf, "--package-out", tmp_path, "--density", "50")
    assert result.returncode == 0, result.stderr
    assert ("link 'spacer': no <inertial>: no geometry either, given the default mass 0.01 kg and inertia 1e-06 kg m^2"
            in result.stderr)
    assert "link 'shown': mass 0 is not > 0: inertia computed from its visual geometry" in result.stderr
    links = {link.get("name"): link for link in ET.parse(tmp_path / "bare_sixdof_config/urdf/bare.urdf").getroot()
             .findall("link")}
    assert float(links["spacer"].find("inertial/mass").get("value")) == 0.01
    shown = links["shown"].findall("inertial")
    assert len(shown) == 1  # replaced, not added
    assert float(shown[0].find("mass").get("value")) == pytest.approx(1000 * math.pi * 0.02**2 * 0.2, rel=1e-6)
    assert shown[0].find("origin").get("xyz") == "0 0 0.1"
