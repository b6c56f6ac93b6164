"""Helpers of the setup assistant's tests: run `setup_assistant` from the source tree against the sourced workspace's
setup_assistant_core."""

from __future__ import annotations

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1]
REPO = PACKAGE.parents[1]
SCRIPT = PACKAGE / "scripts" / "setup_assistant"
ROBOTS = REPO / "test" / "robots"
SIXDOF_DESCRIPTION = REPO / "sixdof_description"
FIXTURES = {
    "ur_like": ROBOTS / "urdf" / "ur_like.urdf.xacro",
    "seven_dof": ROBOTS / "urdf" / "seven_dof.urdf.xacro",
    "mounted": ROBOTS / "urdf" / "mounted.urdf",
    "sixdof": SIXDOF_DESCRIPTION / "urdf" / "sixdof.urdf",
}


def environment() -> dict[str, str]:
    env = dict(os.environ)
    # The fixture robots' package (for $(find sixdof_test_robots)) and sixdof_description's meshes.
    env["ROS_PACKAGE_PATH"] = os.pathsep.join([str(ROBOTS), str(REPO), env.get("ROS_PACKAGE_PATH", "")])
    return env


def run(*args: str | Path, check: bool = False) -> subprocess.CompletedProcess:
    result = subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], env=environment(), capture_output=True,
                            text=True, timeout=300)
    if check and result.returncode != 0:
        raise AssertionError(f"setup_assistant failed ({result.returncode}): {result.stderr}")
    return result


def srdf(path: Path) -> ET.Element:
    return ET.parse(path).getroot()


@pytest.fixture(scope="session")
def generated(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Every fixture robot's package, generated once at a low density."""
    out = tmp_path_factory.mktemp("packages")
    packages = {}
    for robot, urdf in FIXTURES.items():
        run("--urdf", urdf, "--package-out", out, "--density", "1000", check=True)
        packages[robot] = out / f"{robot}_sixdof_config"
    return packages
