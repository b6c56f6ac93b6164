"""config/world_pack.yaml of every fixture robot's package: the simulator loads it with the robot, and the robot's IK
(sixdof_core's bindings, the package's kinematics.yaml solver) reaches top-down tool poses along the belt's pick
zone and over the box's slots."""

from __future__ import annotations

import math
import os
import subprocess
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import rosgraph
import yaml
from conftest import FIXTURES

import sixdof_core
from sixdof_setup_assistant.packing_world import pick_zone
from sixdof_test_support.processes import free_port, stop

# Outcome bound only: the simulator loads a world and a robot in about a second.
LOAD_TIMEOUT = 60.0


def load(package: Path, rel: str) -> dict:
    return yaml.safe_load((package / rel).read_text())


def arm_chain(package: Path, robot: str) -> tuple[str, str]:
    """(group, tip link) of the SRDF's chain group."""
    root = ET.parse(package / f"config/{robot}.srdf").getroot()
    group = next(g for g in root.findall("group") if g.find("chain") is not None)
    return group.get("name"), group.find("chain").get("tip_link")


@pytest.mark.parametrize("robot", list(FIXTURES))
def test_the_tool_reaches_the_belt_and_the_box_pointing_down(generated: dict[str, Path], robot: str) -> None:
    package = generated[robot]
    text = (package / "config/world_pack.yaml").read_text()
    world = yaml.safe_load(text)
    belt, box = world["conveyors"][0], world["bins"][0]
    assert belt["rpy"] == [0.0, 0.0, pytest.approx(math.pi / 2)]  # along world +y
    group, tip = arm_chain(package, robot)
    model = sixdof_core.RobotModel.from_files(str(package / f"urdf/{robot}.urdf"),
                                              str(package / f"config/{robot}.srdf"))
    grasping = package / "config/grasping.yaml"
    tool = load(package, "config/grasping.yaml")["tcp"]["frame"] if grasping.is_file() else tip
    state = sixdof_core.RobotState(model)
    tip_in_tool = np.linalg.inv(state.link_pose(tool)) @ state.link_pose(tip)
    ik = sixdof_core.create_ik_solver(load(package, "config/kinematics.yaml")[group]["kinematics_solver"], model,
                                      group)
    options = sixdof_core.IkOptions(timeout=0.0, attempts=50, random_seed=7)

    def reached(x: float, y: float, z: float) -> bool:
        tool_pose = sixdof_core.pose_from_xyz_rpy(x, y, z, math.pi, 0.0, math.atan2(y, x) + math.pi)
        return bool(ik.solve(tool_pose @ tip_in_tool, options))

    top = belt["position"][2] + belt["size"][2] / 2
    low, high = pick_zone(text)
    assert belt["size"][0] / 2 > high > low > -belt["size"][0] / 2 and high - low >= 0.1
    source = world["sources"][0]["position"][0]
    assert source < low  # upstream of the pick zone
    missed = []
    steps = max(2, math.ceil((high - low) / 0.04))
    for i in range(steps + 1):
        y = belt["position"][1] + low + (high - low) * i / steps
        for z in (top + 0.015, top + 0.11):
            if not reached(belt["position"][0], y, z):
                missed.append(("belt", y, z))
    inside = box["size"][0] - 2 * box["wall_thickness"]
    for dx in (-inside / 4, inside / 4):
        for dy in (-inside / 4, inside / 4):
            for z in (box["position"][2] + 0.015, box["position"][2] + 0.12):
                x, y = box["position"][0] + dx, box["position"][1] + dy
                if not reached(x, y, z):
                    missed.append(("slot", x, y, z))
    assert not missed, missed
    table = world["tables"][0]
    for x, y in ((belt["position"][0], belt["position"][1] + s * belt["size"][0] / 2) for s in (-1, 1)):
        assert abs(x - table["position"][0]) < table["size"][0] / 2 and abs(y) < table["size"][1] / 2
    assert "config/world_pack.yaml" in (package / "README.md").read_text()


@pytest.mark.parametrize("robot", list(FIXTURES))
def test_the_simulator_loads_it(generated: dict[str, Path], robot: str, tmp_path: Path) -> None:
    package = generated[robot]
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://localhost:{port}", ROS_HOME=str(tmp_path),
               ROS_LOG_DIR=str(tmp_path / "log"))
    grasping = package / "config/grasping.yaml"
    # sixdof_sim's sim.launch with the package's files (an arg given as "" on roslaunch's command line is not empty).
    args = {"urdf": f"{package}/urdf/{robot}.urdf", "srdf": f"{package}/config/{robot}.srdf",
            "kinematics": f"{package}/config/kinematics.yaml", "joint_limits": f"{package}/config/joint_limits.yaml",
            "grasping": str(grasping) if grasping.is_file() else "",
            "controllers_file": f"{package}/config/controllers.yaml", "world": f"{package}/config/world_pack.yaml",
            "real_time_factor": "0", "robot_state_publisher": "false"}
    sim = tmp_path / "sim.launch"
    sim.write_text('<launch><include file="$(find sixdof_sim)/launch/sim.launch">'
                   + "".join(f'<arg name="{k}" value="{v}"/>' for k, v in args.items()) + "</include></launch>")
    log = tmp_path / "sim.log"
    with open(log, "w") as out:
        launch = subprocess.Popen(["roslaunch", "-p", str(port), str(sim)], stdout=out,
                                  stderr=subprocess.STDOUT, env=env, start_new_session=True)
    try:
        master = rosgraph.Master("/test_packing_world", master_uri=env["ROS_MASTER_URI"])
        deadline = time.monotonic() + LOAD_TIMEOUT
        loaded = None
        while loaded is None:
            assert launch.poll() is None, f"the simulator ended:\n{log.read_text()[-3000:]}"
            assert time.monotonic() < deadline, f"no /sixdof_sim/world within {LOAD_TIMEOUT} s:\n{log.read_text()}"
            try:
                loaded = master.getParam("/sixdof_sim/world")
            except (OSError, rosgraph.MasterError):
                time.sleep(0.2)
    finally:
        stop(launch, 30.0)
    assert [c["name"] for c in loaded["conveyors"]] == ["belt"]
    assert [s["name"] for s in loaded["sources"]] == ["part"]
    assert [b["name"] for b in loaded["bins"]] == ["box"]
    assert {s["name"] for s in loaded["sinks"]} == {"belt_end", "floor"}
