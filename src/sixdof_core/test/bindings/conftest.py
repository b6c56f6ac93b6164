"""Fixtures of the bindings' tests: the robots of the core's C++ tests (the sixdof arm of this checkout, the
fixtures of test/data), loaded through sixdof_core, and a table-top scene. No ROS master is involved."""

from __future__ import annotations

import os
import sys
from pathlib import Path

# The build under test (CMake sets it to its devel space), else the sourced workspace's.
BUILD_PYTHONPATH = os.environ.get("SIXDOF_CORE_PYTHONPATH", "")
if BUILD_PYTHONPATH:
    sys.path.insert(0, BUILD_PYTHONPATH)

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import sixdof_core  # noqa: E402

CORE = Path(__file__).resolve().parents[2]
DATA = CORE / "test" / "data"
# The sixdof arm of the sourced workspace: sixdof_description depends on this package, so it is found when the tests
# run, not declared.
DESCRIPTION = Path(sixdof_core.find_package("sixdof_description"))


def arm_model() -> sixdof_core.RobotModel:
    return sixdof_core.RobotModel.from_files(str(DESCRIPTION / "urdf" / "sixdof.urdf"),
                                             str(DESCRIPTION / "config" / "sixdof.srdf"),
                                             package_dirs={"sixdof_description": str(DESCRIPTION)})


@pytest.fixture(scope="session")
def arm() -> sixdof_core.RobotModel:
    return arm_model()


@pytest.fixture(scope="session")
def joint_kinds() -> sixdof_core.RobotModel:
    return sixdof_core.RobotModel.from_files(str(DATA / "joint_kinds.urdf"), str(DATA / "joint_kinds.srdf"))


@pytest.fixture(scope="session")
def ur_like() -> sixdof_core.RobotModel:
    return sixdof_core.RobotModel.from_files(str(DATA / "ur_like.urdf"), str(DATA / "ur_like.srdf"),
                                             package_dirs={"sixdof_core": str(CORE)})


@pytest.fixture()
def table_scene(arm: sixdof_core.RobotModel) -> sixdof_core.CollisionScene:
    """The arm on a table (top at z = 0) with a box on it at (0.40, -0.15)."""
    scene = sixdof_core.CollisionScene(arm)
    scene.add_box("table", [1.2, 1.2, 0.05], sixdof_core.pose_from_xyz_rpy(0.3, 0.0, -0.025, 0.0, 0.0, 0.0))
    scene.add_box("cube", [0.04, 0.04, 0.04], sixdof_core.pose_from_xyz_rpy(0.40, -0.15, 0.02, 0.0, 0.0, 0.0))
    scene.set_allowed(arm.root_link, "table")
    return scene


def translation(x: float, y: float, z: float) -> np.ndarray:
    return sixdof_core.pose_from_xyz_rpy(x, y, z, 0.0, 0.0, 0.0)
