"""Shared fixtures: the package's source tree, its URDF/SRDF parsed by urdfdom-py and ElementTree, and the same
files read by sixdof_core (the C++ core's model, for forward and inverse kinematics)."""

import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

PKG = Path(__file__).resolve().parent.parent
# The tests exercise the source tree's generator module, also before it is installed.
sys.path.insert(0, str(PKG / "src"))

from urdf_parser_py import urdf  # noqa: E402

import sixdof_core  # noqa: E402


@pytest.fixture(scope="session")
def pkg() -> Path:
    return PKG


@pytest.fixture(scope="session")
def design() -> dict:
    with open(PKG / "config" / "design.yaml", encoding="utf-8") as f:
        return yaml.safe_load(f)


@pytest.fixture(scope="session")
def robot() -> urdf.Robot:
    return urdf.Robot.from_xml_string((PKG / "urdf" / "sixdof.urdf").read_text(encoding="utf-8"))


@pytest.fixture(scope="session")
def srdf() -> ET.Element:
    return ET.parse(PKG / "config" / "sixdof.srdf").getroot()


@pytest.fixture(scope="session")
def core_model() -> sixdof_core.RobotModel:
    """The committed URDF and SRDF as the core reads them (independently of the generator's own data)."""
    return sixdof_core.RobotModel.from_files(str(PKG / "urdf" / "sixdof.urdf"), str(PKG / "config" / "sixdof.srdf"),
                                             package_dirs={"sixdof_description": str(PKG)})
