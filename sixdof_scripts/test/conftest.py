"""Shared fixtures: the fixture robot (test/data) as move_group's model of it (core_model) and resolved."""

from pathlib import Path

import pytest
from core_model import load_model
from sixdof_commander.goals import GoalBuilder
from sixdof_commander.robot_model import resolve_group

DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(scope="session")
def model():
    return load_model((DATA / "fixture.urdf").read_text(), (DATA / "fixture.srdf").read_text())


@pytest.fixture(scope="session")
def urdf(model):
    return model[0]


@pytest.fixture(scope="session")
def srdf(model):
    return model[1]


@pytest.fixture(scope="session")
def arm(urdf, srdf):
    return resolve_group(urdf, srdf, "arm")


@pytest.fixture()
def builder(arm):
    return GoalBuilder(arm, "base_link")
