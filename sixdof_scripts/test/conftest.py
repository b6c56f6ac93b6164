"""Shared fixtures: the fixture robot (test/data) parsed and resolved."""

from pathlib import Path

import pytest
from sixdof_commander.goals import GoalBuilder
from sixdof_commander.robot_model import parse_srdf, parse_urdf, resolve_group

DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(scope="session")
def urdf():
    return parse_urdf((DATA / "fixture.urdf").read_text())


@pytest.fixture(scope="session")
def srdf():
    return parse_srdf((DATA / "fixture.srdf").read_text())


@pytest.fixture(scope="session")
def arm(urdf, srdf):
    return resolve_group(urdf, srdf, "arm")


@pytest.fixture()
def builder(arm):
    return GoalBuilder(arm, "base_link")
