"""The rosrun scripts' command lines: help works and bad arguments exit 2 before touching ROS."""

import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1]
SCRIPTS = ["scripts/pick_place.py", "scripts/move_to_pose.py", "scripts/move_to_named.py", "scripts/pack_objects.py"]


def run(script, *args):
    return subprocess.run(
        [sys.executable, str(PACKAGE / script), *args], capture_output=True, text=True, timeout=60, check=False
    )


@pytest.mark.parametrize("script", SCRIPTS)
def test_help(script):
    result = run(script, "--help")
    assert result.returncode == 0, result.stderr
    assert "usage:" in result.stdout


@pytest.mark.parametrize(
    ("script", "args", "message"),
    [
        ("scripts/pick_place.py", ["--repetitions", "0"], "--repetitions must be >= 1"),
        ("scripts/pick_place.py", ["--place", "0.4"], "--place: expected 2 arguments"),
        ("scripts/pick_place.py", ["--tolerance", "-1"], "--tolerance must be > 0"),
        ("scripts/move_to_pose.py", ["0.3", "0", "0.3"], "the following arguments are required"),
        ("scripts/move_to_pose.py", ["0.3", "0", "0.3", "a", "0", "0"], "invalid float value: 'a'"),
        ("scripts/move_to_named.py", [], "give a named state or --list"),
        ("scripts/pack_objects.py", [], "the following arguments are required: --box"),
        ("scripts/pack_objects.py", ["--box", "b", "--pattern", "2by2"], "--pattern: pattern must be ROWSxCOLUMNS"),
        ("scripts/pack_objects.py", ["--box", "b", "--pattern", "0x2"], "--pattern: pattern must be ROWSxCOLUMNS"),
        ("scripts/pack_objects.py", ["--box", "b", "--boxes", "0"], "--boxes must be >= 1"),
        ("scripts/pack_objects.py", ["--box", "b", "--pattern", "2x2", "--pattern-file", "p.yaml"], "not allowed with"),
        ("scripts/pack_objects.py", ["--box", "b", "--timeout", "0"], "--timeout must be > 0"),
        ("scripts/pack_objects.py", ["--box", "b", "--velocity-scaling", "2"], "--velocity-scaling must be in (0, 1]"),
    ],
)
def test_bad_arguments_exit_2(script, args, message):
    result = run(script, *args)
    assert result.returncode == 2
    assert message in result.stderr
