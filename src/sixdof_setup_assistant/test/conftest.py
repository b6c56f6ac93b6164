"""Helpers of the setup assistant's tests: run `setup_assistant` from the source tree against the sourced workspace's
setup_assistant_core, on the installed fixture robots (sixdof_test_robots) and the sixdof arm (sixdof_description,
found on ROS_PACKAGE_PATH at run time: it depends on this package, so it cannot be a declared dependency)."""

from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import rospkg

PACKAGE = Path(__file__).resolve().parents[1]
SCRIPT = PACKAGE / "scripts" / "setup_assistant"
ROBOTS = Path(rospkg.RosPack().get_path("sixdof_test_robots"))
SIXDOF_DESCRIPTION = Path(rospkg.RosPack().get_path("sixdof_description"))
FIXTURES = {
    "ur_like": ROBOTS / "urdf" / "ur_like.urdf.xacro",
    "seven_dof": ROBOTS / "urdf" / "seven_dof.urdf.xacro",
    "mounted": ROBOTS / "urdf" / "mounted.urdf",
    "sixdof": SIXDOF_DESCRIPTION / "urdf" / "sixdof.urdf",
}


def run(*args: str | Path, check: bool = False) -> subprocess.CompletedProcess:
    result = subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True, timeout=300)
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
