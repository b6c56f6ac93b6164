"""Issue #10 6(a), #21: sixdof_description's committed config (SRDF, kinematics, joint limits, controllers,
grasping.yaml) is what the setup assistant generates for the arm with the answers its CAD generator writes
(config/setup_answers.yaml)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from conftest import FIXTURES, SIXDOF_DESCRIPTION, run, srdf

CONFIG = SIXDOF_DESCRIPTION / "config"


@pytest.fixture(scope="module")
def package(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("sixdof")
    run("--urdf", FIXTURES["sixdof"], "--package-out", out, "--answers", CONFIG / "setup_answers.yaml", check=True)
    return out / "sixdof_sixdof_config"


def semantic(path: Path) -> dict:
    root = srdf(path)
    return {
        "robot": root.get("name"),
        "groups": [(g.get("name"), [(c.tag, sorted(c.attrib.items())) for c in g]) for g in root.findall("group")],
        "states": sorted((s.get("group"), s.get("name"), sorted((j.get("name"), float(j.get("value")))
                                                                  for j in s.findall("joint")))
                         for s in root.findall("group_state")),
        "end_effectors": [sorted(e.attrib.items()) for e in root.findall("end_effector")],
        "virtual_joints": [sorted(e.attrib.items()) for e in root.findall("virtual_joint")],
        "disabled": sorted((d.get("link1"), d.get("link2"), d.get("reason"))
                           for d in root.findall("disable_collisions")),
    }


def load(path: Path) -> dict:
    return yaml.safe_load(path.read_text())


def test_srdf_is_the_generated_one(package: Path) -> None:
    assert semantic(package / "config/sixdof.srdf") == semantic(CONFIG / "sixdof.srdf")


def test_kinematics_and_joint_limits_are_the_generated_ones(package: Path) -> None:
    assert load(package / "config/kinematics.yaml") == load(CONFIG / "kinematics.yaml")
    assert load(package / "config/joint_limits.yaml") == load(CONFIG / "joint_limits.yaml")
    assert "# defaulted" not in (package / "config/joint_limits.yaml").read_text()  # all from the design


def test_controllers_are_the_generated_ones(package: Path) -> None:
    generated, committed = load(package / "config/controllers.yaml"), load(CONFIG / "controllers.yaml")
    assert generated["controller_list"] == committed["controller_list"]
    assert list(generated) == list(committed)
    for name, controller in committed.items():
        if name == "controller_list":
            continue
        # The design adds PID gains from its masses (for effort-controlled hardware; the simulator's position
        # servos and move_group do not read them): everything else is the generator's.
        assert generated[name] == {k: v for k, v in controller.items() if k != "gains"}, name


def test_grasping_is_the_generated_one(package: Path) -> None:
    # With the URDF's gazebo_grasp_fix settings as answers (the paper's 100 deg, 4 Hz, 4 of 8).
    assert (package / "config/grasping.yaml").read_text() == (CONFIG / "grasping.yaml").read_text()
    fix = load(CONFIG / "grasping.yaml")["grasp_fix"]
    assert (fix["forces_angle_tolerance"], fix["update_rate"], fix["grip_count_threshold"], fix["max_grip_count"]) == (
        100, 4, 4, 8)


def test_hardware_is_the_generated_one(package: Path) -> None:
    assert load(package / "config/hardware.yaml") == load(CONFIG / "hardware.yaml")


def test_the_urdf_is_used_as_it_is(package: Path) -> None:
    assert (package / "urdf/sixdof.urdf").read_text() == FIXTURES["sixdof"].read_text()
