"""What the tests of generated config packages share (any_arm.py, external_driver.py): a ROS master of the test's
own, a temporary workspace on ROS_PACKAGE_PATH, a fixture robot's package written by the setup assistant, and
stopping launched process groups."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import time
from pathlib import Path

import rosgraph
from e2e import STARTUP_TIMEOUT

REPO = Path(__file__).resolve().parents[2]
FIXTURES = REPO / "test" / "robots"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop(process: subprocess.Popen, timeout: float = 60.0) -> None:
    """SIGINT to the process group (roslaunch stops its nodes), SIGKILL if it is still there after timeout."""
    if process.poll() is not None:
        return
    os.killpg(process.pid, signal.SIGINT)
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()


def start_master(root: Path) -> subprocess.Popen:
    """A roscore on a free port for this process and its children (ROS_MASTER_URI), with root (and the fixture
    robots' package) on ROS_PACKAGE_PATH and the logs under root; returns once the master answers."""
    port = free_port()
    os.environ["ROS_MASTER_URI"] = f"http://localhost:{port}"
    os.environ["ROS_PACKAGE_PATH"] = os.pathsep.join([str(root), str(FIXTURES), os.environ.get("ROS_PACKAGE_PATH", "")])
    os.environ["ROS_LOG_DIR"] = str(root / "log")
    with open(root / "roscore.log", "w") as log:
        core = subprocess.Popen(
            ["roscore", "-p", str(port)], stdout=log, stderr=subprocess.STDOUT, start_new_session=True
        )
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while not rosgraph.is_master_online():
        assert core.poll() is None, f"roscore exited (see {root / 'roscore.log'})"
        assert time.monotonic() < deadline, "the ROS master did not come up"
        time.sleep(0.2)
    return core


def generate_package(robot: str, description: str, workspace: Path) -> tuple[str, Path]:
    """The setup assistant's config package of the fixture robot `robot` (description: its file in test/robots)
    written into workspace: (package name, its folder)."""
    generated = subprocess.run(
        ["rosrun", "sixdof_core", "setup_assistant", "--urdf", str(FIXTURES / description), "--package-out",
         str(workspace)],
        capture_output=True,
        text=True,
        timeout=STARTUP_TIMEOUT,
    )
    assert generated.returncode == 0, f"setup_assistant failed on {description}: {generated.stderr}"
    name = f"{robot}_sixdof_config"
    package = workspace / name
    assert (package / "launch" / "demo.launch").is_file(), generated.stdout
    return name, package
