"""A stack that cannot start says so: when the simulator refuses its world or its URDF at start-up, demo.launch ends
(its startup_watch node is required) with the simulator's one-line error, instead of leaving move_group and
scene_mirror waiting for a clock that never comes. Each case launches demo.launch headless with its own master.
(A simulator dying later, with sim_respawn, keeps running the stack: test/ros/faults.test.)

    python -m pytest test/ros/startup_failure.py
"""

from __future__ import annotations

import os
import re
import subprocess
import time
from pathlib import Path

import rospkg
from generated import free_port, stop

# Outcome bound only: a healthy stack's nodes are up in seconds; one that fails ends in about as long.
END_TIMEOUT = 120.0
WATCH_LINE = re.compile(r"^\[startup_watch\] /sixdof_sim could not start: (.*)$", re.MULTILINE)


def run_demo(tmp_path: Path, *args: str, until: str = "") -> tuple[int | None, str]:
    """demo.launch headless with `args` on a master of its own until it ends, or its output has a line containing
    `until`, or END_TIMEOUT s have passed: (its exit code, None if it was still running and had to be stopped; its
    output)."""
    env = dict(os.environ, ROS_HOME=str(tmp_path / "ros"), ROS_LOG_DIR=str(tmp_path / "log"))
    port = free_port()
    env["ROS_MASTER_URI"] = f"http://localhost:{port}"
    out = tmp_path / "launch.out"
    with open(out, "w") as log:
        launch = subprocess.Popen(
            ["roslaunch", "-p", str(port), "sixdof_bringup", "demo.launch", "headless:=true", *args],
            stdout=log,
            stderr=subprocess.STDOUT,
            env=env,
            start_new_session=True,
        )
    deadline = time.monotonic() + END_TIMEOUT
    while launch.poll() is None and time.monotonic() < deadline and not (until and until in out.read_text()):
        time.sleep(0.2)
    code = launch.poll()
    stop(launch)
    return code, out.read_text()


def watch_line(output: str) -> str:
    found = WATCH_LINE.findall(output)
    assert len(found) == 1, f"expected one startup_watch line, got {found}:\n{output[-3000:]}"
    return found[0]


def test_a_bad_world_ends_the_launch_with_its_error(tmp_path: Path) -> None:
    world = tmp_path / "bad_world.yaml"
    world.write_text("name: bad\ntables: []\nobjets: []\n")
    code, output = run_demo(tmp_path, f"world:={world}")
    assert code is not None, f"demo.launch kept running with a world the simulator refuses:\n{output[-3000:]}"
    error = watch_line(output)
    assert "unknown key 'objets'" in error and str(world) in error, error
    # The launch's nodes are gone with it: nothing waits for a clock.
    assert "REQUIRED process [startup_watch" in output, output[-3000:]


def test_a_bad_urdf_ends_the_launch_with_its_error(tmp_path: Path) -> None:
    # The sixdof arm with a finger that has no <inertial>: move_group plans with it, the simulator refuses it.
    urdf = (Path(rospkg.RosPack().get_path("sixdof_description")) / "urdf" / "sixdof.urdf").read_text()
    finger = re.search(r'<link name="finger1">.*?</link>', urdf, re.DOTALL)
    assert finger is not None
    without = re.sub(r"<inertial>.*?</inertial>", "", finger.group(0), flags=re.DOTALL)
    bad = tmp_path / "no_finger_inertia.urdf"
    bad.write_text(urdf.replace(finger.group(0), without))
    code, output = run_demo(tmp_path, f"urdf:={bad}")
    assert code is not None, f"demo.launch kept running with a URDF the simulator refuses:\n{output[-3000:]}"
    error = watch_line(output)
    assert "link 'finger1' cannot be simulated" in error, error


def test_a_good_stack_keeps_running(tmp_path: Path) -> None:
    code, output = run_demo(tmp_path, until="is up (first /clock)")
    assert code is None, f"demo.launch ended (code {code}):\n{output[-3000:]}"
    assert "/sixdof_sim is up (first /clock): watching ends" in output, output[-3000:]
    assert not WATCH_LINE.search(output), output[-3000:]
