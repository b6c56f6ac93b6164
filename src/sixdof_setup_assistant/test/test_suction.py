"""Suction tools: the cup found by its name, its shape or the answers (sixdof_setup_assistant.suction, on URDF text,
no core), and the package generated for the suction fixture robot (grasping.yaml's `suction`, the TCP link at the
cup's face, the SRDF's group and end effector, the README)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml
from conftest import FIXTURES, ROBOTS, run, srdf

from sixdof_setup_assistant.generator import run_core
from sixdof_setup_assistant.infer import InferenceError
from sixdof_setup_assistant.suction import find_tool, with_tcp_link
from sixdof_setup_assistant.xacro_loader import load_description

SUCTION = ROBOTS / "urdf" / "six_r_suction.urdf.xacro"
# The fixture's cup: 3 cm long on tool0, whose z is link_6's x: the face is 3 cm along link_6's x.
FACE = [0.03, 0.0, 0.0]
FACE_RPY = [0.0, math.pi / 2, 0.0]


def describe(urdf: str, tmp_path: Path, xacro_args: dict[str, str] | None = None) -> dict:
    """The core's model description of a URDF or xacro file (what the front end infers from)."""
    text = tmp_path / "robot.urdf"
    text.write_text(load_description(urdf, xacro_args or {}))
    run_core(["--urdf", str(text), "--describe", str(tmp_path / "model.yaml")], echo=False)
    return yaml.safe_load((tmp_path / "model.yaml").read_text())


def tool_model(*tool: tuple[str, list[dict]]) -> dict:
    """A two-joint arm's description (tip `link2`) with the tool's links (name, shapes) fixed below the tip."""
    links = [{"name": name, "shapes": []} for name in ("base", "link1", "link2")]
    joints = [{"name": "j1", "type": "revolute", "parent": "base", "child": "link1", "xyz": [0, 0, 0]},
              {"name": "j2", "type": "revolute", "parent": "link1", "child": "link2", "xyz": [0, 0, 0.3]}]
    for name, shapes in tool:
        links.append({"name": name, "shapes": shapes})
        joints.append({"name": f"{name}_mount", "type": "fixed", "parent": "link2", "child": name, "xyz": [0, 0, 0]})
    for joint in joints:
        joint["rpy"] = [0, 0, 0]
    return {"robot": "r", "root_link": "base", "links": links, "joints": joints}


def cylinder(name: str, length: float, z: float = 0.0) -> tuple[str, list[dict]]:
    return name, [{"type": "cylinder", "radius": 0.02, "length": length, "xyz": [0, 0, z], "rpy": [0, 0, 0]}]


def test_the_cup_is_found_by_its_name(tmp_path: Path) -> None:
    tool = find_tool(describe(str(SUCTION), tmp_path), "link_6", {})
    assert (tool.cup_link, tool.found_by, tool.parent_link) == ("suction_cup", "name", "link_6")
    assert tool.tcp_xyz == pytest.approx(FACE, abs=1e-9) and tool.tcp_rpy == pytest.approx(FACE_RPY, abs=1e-9)
    assert tool.approach == pytest.approx([1.0, 0.0, 0.0], abs=1e-9) and tool.add_tcp_link


def test_an_unnamed_short_cylinder_is_found_by_its_shape(tmp_path: Path) -> None:
    tool = find_tool(describe(str(SUCTION), tmp_path, {"cup": "nozzle"}), "link_6", {})
    assert (tool.cup_link, tool.found_by) == ("nozzle", "shape")
    assert tool.tcp_xyz == pytest.approx(FACE, abs=1e-9)


def test_the_face_is_the_end_away_from_the_arm() -> None:
    # A cylinder centred 2 cm below link2 along -z: its far end is at z = -0.035, the approach is -z.
    tool = find_tool(tool_model(cylinder("nozzle", 0.03, -0.02)), "link2", {})
    assert tool.tcp_xyz == pytest.approx([0.0, 0.0, -0.035]) and tool.approach == pytest.approx([0.0, 0.0, -1.0])


def test_no_cup_no_tool(tmp_path: Path) -> None:
    assert find_tool(describe(str(FIXTURES["ur_like"]), tmp_path), "wrist_3_link", {}) is None
    # A long cylinder (a rod) is no cup.
    assert find_tool(tool_model(cylinder("rod", 0.2)), "link2", {}) is None


def test_the_answers_name_the_cup_and_set_its_payload() -> None:
    answers = {"suction": {"cup_link": "rod", "max_payload": 1.5}}
    tool = find_tool(tool_model(cylinder("rod", 0.2)), "link2", answers)
    assert (tool.cup_link, tool.found_by) == ("rod", "answers")
    assert tool.settings == {"max_payload": 1.5, "tilt_tolerance": 0.2, "contact_distance": 0.003}


@pytest.mark.parametrize(("tool", "answers", "message"), [
    ([cylinder("cup_a", 0.02), cylinder("cup_b", 0.02)], {}, "several links below 'link2' look like"),
    ([cylinder("rod", 0.2)], {"suction": {"cup_link": "cup"}}, "no link 'cup'"),
    ([cylinder("rod", 0.2)], {"suction": {"cup_link": "link1"}}, "'link1' is not fixed below the arm's tip"),
    ([cylinder("rod", 0.2)], {"suction": {"max_payload": 1.0}}, "no cup link found below the arm's tip"),
])
def test_bad_cups_are_named(tool: list, answers: dict, message: str) -> None:
    with pytest.raises(InferenceError, match=message):
        find_tool(tool_model(*tool), "link2", answers)


def test_the_tcp_link_is_added_at_the_face(tmp_path: Path) -> None:
    urdf = ROBOTS / "urdf" / "six_r_suction.urdf.xacro"
    tool = find_tool(describe(str(urdf), tmp_path), "link_6", {})
    added = tmp_path / "with_tcp.urdf"
    added.write_text(with_tcp_link(load_description(str(urdf), {}), tool))
    again = find_tool(describe(str(added), tmp_path), "link_6", {})
    # Found again, the URDF's own `tcp` (at the face, z along the approach) is the TCP.
    assert again.tcp_source == "link 'tcp'" and not again.add_tcp_link
    assert again.tcp_xyz == pytest.approx(FACE, abs=1e-9) and again.tcp_rpy == pytest.approx(FACE_RPY, abs=1e-9)
    # Centred on the tip's origin, a cylinder's ends are equally far: its +z end is the face.
    assert find_tool(tool_model(cylinder("cup", 0.02)), "link2", {}).tcp_xyz == pytest.approx([0.0, 0.0, 0.01])


@pytest.fixture(scope="module")
def package(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("suction")
    run("--urdf", SUCTION, "--package-out", out, "--density", "300", check=True)
    return out / "six_r_suction_sixdof_config"


def test_the_package_of_a_suction_arm(package: Path) -> None:
    data = yaml.safe_load((package / "config/grasping.yaml").read_text())
    assert data["group"] == "gripper" and data["end_effector"] == "hand"
    assert data["tcp"]["parent_link"] == "link_6" and data["tcp"]["xyz"] == pytest.approx(FACE, abs=1e-9)
    assert data["suction"] == {"cup_link": "tcp", "max_payload": 0.5, "tilt_tolerance": 0.2,
                               "contact_distance": 0.003, "controller": "gripper_controller", "arm_name": "arm"}
    root = srdf(package / "config/six_r_suction.srdf")
    group = next(g for g in root.findall("group") if g.get("name") == "gripper")
    assert [link.get("name") for link in group.findall("link")] == ["suction_cup"] and not group.findall("joint")
    ee = root.find("end_effector")
    assert (ee.get("name"), ee.get("parent_link"), ee.get("group")) == ("hand", "link_6", "gripper")
    urdf = ET.parse(package / "urdf/six_r_suction.urdf").getroot()
    assert any(j.find("child").get("link") == "tcp" for j in urdf.findall("joint"))
    controllers = yaml.safe_load((package / "config/controllers.yaml").read_text())
    assert [c["name"] for c in controllers["controller_list"]] == ["arm_controller"]
    readme = (package / "README.md").read_text()
    assert "## Suction tool" in readme and "its name says cup/suction/vacuum" in readme


def test_a_suction_answer_on_a_gripper_is_refused(tmp_path: Path) -> None:
    answers = tmp_path / "answers.yaml"
    answers.write_text("suction: {cup_link: link7}\n")
    result = run("--urdf", FIXTURES["seven_dof"], "--package-out", tmp_path, "--answers", answers)
    assert result.returncode == 2 and "a suction tool has none" in result.stderr
