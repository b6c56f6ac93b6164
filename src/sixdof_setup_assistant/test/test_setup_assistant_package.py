"""`setup_assistant --package-out` on the four fixture robots: files, inference, bad input, re-runs."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml
from conftest import FIXTURES, ROBOTS, run, srdf

FILES = ["package.xml", "CMakeLists.txt", "README.md", "config/kinematics.yaml", "config/joint_limits.yaml",
         "config/controllers.yaml", "config/world.yaml", "config/motion_planning.rviz", "launch/demo.launch",
         "launch/move_group.launch", "launch/real.launch", "config/hardware.yaml", ".setup_assistant.yaml"]

# robot -> (arm chain base, tip, arm joint count, solver, gripper joints, virtual joint)
EXPECTED = {
    "ur_like": ("base_link", "wrist_3_link", 6, "numeric", [], True),
    "seven_dof": ("base_link", "link7", 7, "numeric", ["left_finger_joint", "right_finger_joint"], True),
    "mounted": ("world", "flange", 6, "analytic", [], False),
    "sixdof": ("base_link", "link6", 6, "analytic", ["finger1_joint", "finger2_joint"], True),
}


def tree(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


@pytest.mark.parametrize("robot", list(FIXTURES))
def test_every_file_is_written_and_parses(generated: dict[str, Path], robot: str) -> None:
    package = generated[robot]
    for rel in [*FILES, f"urdf/{robot}.urdf", f"config/{robot}.srdf"]:
        assert (package / rel).is_file(), rel
    for rel in FILES:
        if rel.endswith((".yaml", ".rviz")):
            assert yaml.safe_load((package / rel).read_text()) is not None, rel
    assert ET.parse(package / "package.xml").getroot().findtext("name") == package.name
    ET.parse(package / f"urdf/{robot}.urdf")
    demo = ET.parse(package / "launch/demo.launch").getroot()
    args = {a.get("name"): a for a in demo.findall("arg")}
    assert set(args) == {"rviz", "headless", "world", "real_time_factor", "use_sim_time", "grasp_fix"}
    assert all(a.get("doc") for a in args.values())
    assert demo.find("include").get("file") == "$(find sixdof_bringup)/launch/demo.launch"
    # The grasping information goes to move_group and the simulator; without a gripper none (not the default's).
    has_gripper = bool(EXPECTED[robot][4])
    assert (package / "config/grasping.yaml").is_file() == has_gripper
    for launch in ("demo.launch", "move_group.launch"):
        include = ET.parse(package / "launch" / launch).getroot().find("include")
        passed = {a.get("name"): a.get("value") for a in include.findall("arg")}
        assert passed["grasping"] == (f"$(find {package.name})/config/grasping.yaml" if has_gripper else ""), launch
    world = yaml.safe_load((package / "config/world.yaml").read_text())
    assert [t["name"] for t in world["tables"]] == ["table"] and "objects" not in world
    table = world["tables"][0]
    assert table["position"][2] + table["size"][2] / 2 == pytest.approx(0.0)  # top face under the root frame
    rviz = yaml.safe_load((package / "config/motion_planning.rviz").read_text())
    assert any(p["Class"] == "sixdof_rviz/MotionPlanningPanel" for p in rviz["Panels"])


@pytest.mark.parametrize("robot", list(FIXTURES))
def test_the_real_robot_launch_and_hardware_config(generated: dict[str, Path], robot: str) -> None:
    package = generated[robot]
    real = ET.parse(package / "launch/real.launch").getroot()
    args = {a.get("name"): a for a in real.findall("arg")}
    assert set(args) == {"driver", "port", "rviz", "hardware_file"}
    assert all(a.get("doc") for a in args.values()) and args["driver"].get("default") == "none"
    include = real.find("include")
    assert include.get("file") == "$(find sixdof_bringup)/launch/real.launch"
    passed = {a.get("name") for a in include.findall("arg")}
    assert {"urdf", "srdf", "controllers_file", "hardware_file", "driver", "port", "rviz"} <= passed
    # The hardware gets the controllers' joints less the mimic ones, each with a servo id of its own.
    controllers = yaml.safe_load((package / "config/controllers.yaml").read_text())
    commanded = {j for c in controllers["controller_list"] for j in c["joints"]}
    urdf = ET.parse(package / f"urdf/{robot}.urdf").getroot()
    mimics = {j.get("name") for j in urdf.findall("joint") if j.find("mimic") is not None}
    hardware = yaml.safe_load((package / "config/hardware.yaml").read_text())
    servos = hardware["dynamixel"]["joints"]
    assert set(servos) == commanded - mimics
    assert sorted(s["id"] for s in servos.values()) == list(range(1, len(servos) + 1))
    assert set(hardware["mock"]["initial_positions"]) == set(servos)
    assert hardware["rate"] == 100


@pytest.mark.parametrize("robot", list(FIXTURES))
def test_groups_solver_states_and_controllers_are_inferred(generated: dict[str, Path], robot: str) -> None:
    base, tip, count, solver, fingers, virtual = EXPECTED[robot]
    package = generated[robot]
    root = srdf(package / f"config/{robot}.srdf")
    groups = {g.get("name"): g for g in root.findall("group")}
    chain = groups["arm"].find("chain")
    assert (chain.get("base_link"), chain.get("tip_link")) == (base, tip)
    kinematics = yaml.safe_load((package / "config/kinematics.yaml").read_text())
    assert kinematics["arm"]["kinematics_solver"] == solver
    assert f"# arm: {solver} (" in (package / "config/kinematics.yaml").read_text()  # says why
    controllers = yaml.safe_load((package / "config/controllers.yaml").read_text())
    listed = {c["name"]: c["joints"] for c in controllers["controller_list"]}
    assert len(listed["arm_controller"]) == count
    assert controllers["arm_controller"]["joints"] == listed["arm_controller"]
    states = {(s.get("group"), s.get("name")): {j.get("name"): float(j.get("value")) for j in s.findall("joint")}
              for s in root.findall("group_state")}
    assert list(states[("arm", "home")].values()) == [0.0] * count
    limits = yaml.safe_load((package / "config/joint_limits.yaml").read_text())["joint_limits"]
    assert all(limits[j]["max_acceleration"] > 0 for j in listed["arm_controller"])
    assert "# defaulted" in (package / "config/joint_limits.yaml").read_text()
    if fingers:
        assert [j.get("name") for j in groups["gripper"].findall("joint")] == fingers
        assert listed["gripper_controller"] == fingers
        assert root.find("end_effector").get("parent_link") == tip
        assert set(states[("gripper", "open")].values()) == {0.04}  # the mimic finger follows
        assert set(states[("gripper", "close")].values()) == {0.0}
    else:
        assert "gripper" not in groups and "gripper_controller" not in listed
    assert (root.find("virtual_joint") is not None) == virtual
    reasons = {d.get("reason") for d in root.findall("disable_collisions")}
    assert "Adjacent" in reasons and reasons <= {"Adjacent", "Default", "Always", "Never", "Gripper"}


def test_ur_like_joints_are_continuous_and_xacro_args_pass(tmp_path: Path) -> None:
    result = run("--urdf", FIXTURES["ur_like"], "--package-out", tmp_path, "--density", "200", "--xacro-args",
                 "prefix:=left_ upper_arm:=0.45", "--name", "left_arm_config")
    assert result.returncode == 0, result.stderr
    urdf = ET.parse(tmp_path / "left_arm_config/urdf/ur_like.urdf").getroot()
    joints = {j.get("name"): j for j in urdf.findall("joint")}
    assert joints["left_shoulder_pan_joint"].get("type") == "continuous"
    assert joints["left_elbow_joint"].find("origin").get("xyz").startswith("0.45")
    controllers = yaml.safe_load((tmp_path / "left_arm_config/config/controllers.yaml").read_text())
    assert controllers["arm_controller"]["joints"][0] == "left_shoulder_pan_joint"


def test_answers_override_every_choice(tmp_path: Path) -> None:
    answers = tmp_path / "answers.yaml"
    answers.write_text(yaml.safe_dump({
        "name": "custom_config", "density": 300, "planning_frame": "map",
        "arm": {"group": "manipulator", "tip_link": "link6", "solver": "numeric", "controller": "arm_ctl"},
        "gripper": {"group": "hand_group", "joints": ["left_finger_joint"], "controller": "hand_ctl"},
        "end_effector": {"name": "tool", "parent_link": "hand"},
        "named_states": {"manipulator": {"ready": {"joint1": 0.0, "joint2": 0.5, "joint3": 0.0, "joint4": 1.0,
                                                   "joint5": 0.0, "joint6": 0.0}}},
        "acceleration_limits": {"joint1": 3.5},
    }))
    result = run("--urdf", FIXTURES["seven_dof"], "--package-out", tmp_path, "--answers", answers)
    assert result.returncode == 0, result.stderr
    package = tmp_path / "custom_config"
    root = srdf(package / "config/seven_dof.srdf")
    groups = {g.get("name"): g for g in root.findall("group")}
    assert groups["manipulator"].find("chain").get("tip_link") == "link6"
    assert [j.get("name") for j in groups["hand_group"].findall("joint")] == ["left_finger_joint"]
    assert [(s.get("group"), s.get("name")) for s in root.findall("group_state")] == [
        ("hand_group", "open"), ("hand_group", "close"), ("manipulator", "ready")]
    assert root.find("end_effector").get("name") == "tool"
    assert root.find("virtual_joint").get("parent_frame") == "map"
    assert yaml.safe_load((package / "config/kinematics.yaml").read_text())["manipulator"]["kinematics_solver"] == (
        "numeric")
    controllers = yaml.safe_load((package / "config/controllers.yaml").read_text())
    assert [c["name"] for c in controllers["controller_list"]] == ["arm_ctl", "hand_ctl"]
    limits = yaml.safe_load((package / "config/joint_limits.yaml").read_text())["joint_limits"]
    assert limits["joint1"]["max_acceleration"] == 3.5 and limits["joint2"]["max_acceleration"] == 2 * 1.7


BAD_URDF = '<robot name="broken"><link name="a"/><joint name="j" type="revolute"><parent link="a"/></robot>'


@pytest.mark.parametrize("case", ["malformed_urdf", "malformed_xacro", "unknown_package", "missing_chain",
                                  "state_outside_limits", "unknown_answer_key", "bad_answer_value",
                                  "output_is_a_file", "analytic_that_does_not_fit"])
def test_bad_input_exits_2_with_one_line_and_writes_nothing(tmp_path: Path, case: str) -> None:
    inputs = tmp_path / "inputs"
    inputs.mkdir()
    urdf, answers = FIXTURES["seven_dof"], None
    out = tmp_path / "out"
    if case == "malformed_urdf":
        urdf = inputs / "broken.urdf"
        urdf.write_text(BAD_URDF)
    elif case == "malformed_xacro":
        urdf = inputs / "broken.urdf.xacro"
        urdf.write_text('<robot name="x" xmlns:xacro="http://wiki.ros.org/xacro"><xacro:no_such_macro/></robot>')
    elif case == "unknown_package":
        urdf = inputs / "find.urdf.xacro"
        urdf.write_text('<robot name="x" xmlns:xacro="http://wiki.ros.org/xacro">'
                        '<xacro:include filename="$(find no_such_package_here)/x.xacro"/></robot>')
    elif case == "missing_chain":
        answers = {"arm": {"base_link": "link5", "tip_link": "link2"}}
    elif case == "state_outside_limits":
        answers = {"named_states": {"arm": {"home": {"joint1": 4.0}}}}
    elif case == "unknown_answer_key":
        answers = {"arm": {"tip": "link7"}}
    elif case == "bad_answer_value":
        answers = {"arm": {"solver": "magic"}}
    elif case == "output_is_a_file":
        out.write_text("I am a file")
    elif case == "analytic_that_does_not_fit":
        answers = {"arm": {"solver": "analytic"}}
    args = ["--urdf", urdf, "--package-out", out, "--density", "100"]
    if answers is not None:
        (inputs / "answers.yaml").write_text(yaml.safe_dump(answers))
        args += ["--answers", inputs / "answers.yaml"]
    before = tree(tmp_path)
    result = run(*args)
    assert result.returncode == 2, (case, result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("setup_assistant: "), result.stderr
    assert tree(tmp_path) == before, f"{case} left files behind"
    expected = {"malformed_urdf": "broken.urdf", "malformed_xacro": "broken.urdf.xacro",
                "unknown_package": "no_such_package_here", "missing_chain": "link2",
                "state_outside_limits": "outside its limits", "unknown_answer_key": "arm.tip",
                "bad_answer_value": "arm.solver", "output_is_a_file": "is a file",
                "analytic_that_does_not_fit": "analytic"}[case]
    assert expected in lines[0], lines[0]


def test_bad_arguments_exit_2(tmp_path: Path) -> None:
    for args in (["--urdf", FIXTURES["mounted"]], ["--urdf", FIXTURES["mounted"], "--package-out", tmp_path,
                                                   "--density", "0"],
                 ["--urdf", FIXTURES["mounted"], "--package-out", tmp_path, "--xacro-args", "novalue"]):
        result = run(*args)
        assert result.returncode == 2 and len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert list(tmp_path.iterdir()) == []


def test_rerun_keeps_hand_edits_and_lists_what_it_regenerates(tmp_path: Path) -> None:
    args = ["--urdf", FIXTURES["ur_like"], "--package-out", tmp_path, "--density", "300"]
    run(*args, check=True)
    package = tmp_path / "ur_like_sixdof_config"
    first = {rel: (package / rel).read_bytes() for rel in tree(package) if (package / rel).is_file()}

    again = run(*args, check=True)  # nothing edited: same bytes, all listed as regenerated
    assert "regenerated: " in again.stdout and "kept" not in again.stdout
    assert {rel: (package / rel).read_bytes() for rel in first} == first

    kinematics = package / "config/kinematics.yaml"
    kinematics.write_text(kinematics.read_text().replace("kinematics_solver_timeout: 0.005",
                                                         "kinematics_solver_timeout: 0.05"))
    srdf_path = package / "config/ur_like.srdf"
    text = srdf_path.read_text().replace("</robot>", '  <group_state name="up" group="arm">'
                                         '<joint name="shoulder_lift_joint" value="-1.5"/></group_state>\n'
                                         '  <disable_collisions link1="base_link" link2="forearm_link" '
                                         'reason="User"/>\n</robot>')
    srdf_path.write_text(text)
    (package / "scripts").mkdir()
    (package / "scripts/mine.py").write_text("print('mine')\n")

    third = run(*args, check=True)
    assert "kept (edited by hand; delete to regenerate): config/kinematics.yaml" in third.stdout, third.stdout
    assert "SRDF edited by hand" in third.stdout
    assert "kinematics_solver_timeout: 0.05" in kinematics.read_text()
    root = srdf(srdf_path)
    assert "up" in [s.get("name") for s in root.findall("group_state")]
    assert ("base_link", "forearm_link", "User") in [(d.get("link1"), d.get("link2"), d.get("reason"))
                                                     for d in root.findall("disable_collisions")]
    assert (package / "scripts/mine.py").read_text() == "print('mine')\n"
    assert (package / "launch/demo.launch").read_bytes() == first["launch/demo.launch"]

    fourth = run(*args, check=True)  # still edited: still kept
    assert "config/kinematics.yaml" in fourth.stdout.split("kept")[1]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".setup_assistant")]


def test_files_no_longer_generated_go_unless_edited(tmp_path: Path) -> None:
    run("--urdf", FIXTURES["mounted"], "--package-out", tmp_path, "--name", "arm_config", "--density", "100",
        check=True)
    package = tmp_path / "arm_config"
    (package / "config/mounted.srdf").write_text((package / "config/mounted.srdf").read_text() + "<!-- mine -->\n")
    result = run("--urdf", FIXTURES["ur_like"], "--package-out", tmp_path, "--name", "arm_config", "--density",
                 "100", check=True)
    assert "removed (no longer generated): urdf/mounted.urdf" in result.stdout, result.stdout
    assert not (package / "urdf/mounted.urdf").exists() and (package / "urdf/ur_like.urdf").is_file()
    assert (package / "config/mounted.srdf").read_text().endswith("<!-- mine -->\n")  # edited: kept


def test_a_folder_not_made_by_the_setup_assistant_is_refused(tmp_path: Path) -> None:
    (tmp_path / "mounted_sixdof_config").mkdir()
    (tmp_path / "mounted_sixdof_config/notes.txt").write_text("mine")
    result = run("--urdf", FIXTURES["mounted"], "--package-out", tmp_path, "--density", "100")
    assert result.returncode == 2 and "not generated by setup_assistant" in result.stderr
    assert tree(tmp_path) == ["mounted_sixdof_config", "mounted_sixdof_config/notes.txt"]


def test_srdf_only_mode_takes_xacro(tmp_path: Path) -> None:
    out = tmp_path / "ur_like.srdf"
    result = run("--urdf", FIXTURES["ur_like"], "--srdf-out", out, "--density", "200", "--groups-skeleton")
    assert result.returncode == 0, result.stderr
    root = srdf(out)
    assert root.get("name") == "ur_like" and root.find("group").get("name") == "arm"


def test_progress_is_reported_while_sampling(tmp_path: Path) -> None:
    result = run("--urdf", FIXTURES["mounted"], "--package-out", tmp_path, "--density", "500")
    assert "sampling self-collisions: 500 / 500 (100%)" in result.stdout


def test_fixture_package_resolves_through_ros_package_path() -> None:
    assert (ROBOTS / "package.xml").is_file()
    assert "$(find sixdof_test_robots)" in (ROBOTS / "urdf/ur_like.urdf.xacro").read_text()
    assert os.path.isfile(ROBOTS / "urdf/ur_like_macro.xacro")
