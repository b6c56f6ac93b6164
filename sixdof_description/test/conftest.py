"""Shared fixtures: the package's source tree, its parsed URDF/SRDF and KDL chains built from the URDF."""

import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

PKG = Path(__file__).resolve().parent.parent
# The tests exercise the source tree's generator module, also before it is installed.
sys.path.insert(0, str(PKG / "src"))

from urdf_parser_py import urdf  # noqa: E402

from sixdof_description.kinematics import JointSpec, chain  # noqa: E402


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


def urdf_joint_spec(joint) -> JointSpec:
    origin = joint.origin
    xyz = tuple(origin.xyz) if origin is not None and origin.xyz is not None else (0.0, 0.0, 0.0)
    rpy = tuple(origin.rpy) if origin is not None and origin.rpy is not None else (0.0, 0.0, 0.0)
    axis = tuple(joint.axis) if joint.axis is not None else (1.0, 0.0, 0.0)
    kind = {"revolute": "revolute", "continuous": "revolute", "prismatic": "prismatic"}.get(joint.type, "fixed")
    lower = joint.limit.lower if joint.limit is not None else -math.inf
    upper = joint.limit.upper if joint.limit is not None else math.inf
    return JointSpec(joint.name, xyz, rpy, axis, kind, lower, upper)


def urdf_chain(robot: urdf.Robot, root: str, tip: str):
    """KDL chain root -> tip built from the parsed URDF (independently of the generator's own data)."""
    by_child = {j.child: j for j in robot.joints}
    joints = []
    link = tip
    while link != root:
        if link not in by_child:
            raise KeyError(f"{tip} is not below {root}")
        joints.append(by_child[link])
        link = by_child[link].parent
    specs = [urdf_joint_spec(j) for j in reversed(joints)]
    return chain(specs), [s for s in specs if s.joint_type != "fixed"]
