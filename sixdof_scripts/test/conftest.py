"""Shared fixtures: the fixture robot (test/data) read by the test-only offline_model and resolved."""

from pathlib import Path

import pytest
from offline_model import parse_srdf, parse_urdf
from sixdof_commander.goals import GoalBuilder
from sixdof_commander.robot_model import resolve_group

DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(scope="session")
def urdf():
    return parse_urdf((DATA / "fixture.urdf").read_text())


@pytest.fixture(scope="session")
def srdf(urdf):
    return parse_srdf((DATA / "fixture.srdf").read_text(), urdf)


@pytest.fixture(scope="session")
def arm(urdf, srdf):
    return resolve_group(urdf, srdf, "arm")


@pytest.fixture()
def builder(arm):
    return GoalBuilder(arm, "base_link")
