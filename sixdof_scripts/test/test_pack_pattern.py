"""Packing patterns: ROWSxCOLUMNS[xLAYERS] and pallet-style YAML files, their slots in a box, and bad input."""

import math
import subprocess
import sys
from pathlib import Path

import pytest
from sixdof_commander.pack_pattern import Pattern, PatternError, load_pattern, parse_pattern
from sixdof_commander.sim_world import Bin

PACKAGE = Path(__file__).resolve().parents[1]
# 28 cm outside, 1 cm walls: 26 cm inside, turned by 90 degrees.
BOX = Bin("box", "orange", (0.6, 0.45, 0.3), (0.2, -0.3, 0.0), math.pi / 2.0, (0.28, 0.28), 0.03, 0.01)


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "pattern.yaml"
    path.write_text(text)
    return path


def test_equal_cells_fill_the_box_row_by_row():
    slots = parse_pattern("2x2").slots(BOX)
    # Rows along the box's x axis (world +y here), columns along its y axis (world -x).
    local = [(round(s.y + 0.3, 6), round(0.2 - s.x, 6)) for s in slots]
    assert local == [(-0.065, -0.065), (-0.065, 0.065), (0.065, -0.065), (0.065, 0.065)]
    assert all(s.bottom == 0.0 and s.layer == 0 for s in slots)


def test_layers_stack_after_each_other():
    slots = parse_pattern("1x2x3", layer_height=0.06).slots(BOX)
    assert [s.layer for s in slots] == [0, 0, 1, 1, 2, 2]
    assert [s.bottom for s in slots] == pytest.approx([0.0, 0.0, 0.06, 0.06, 0.12, 0.12])


def test_yaml_pattern_with_spacing_is_centred(tmp_path):
    pattern = load_pattern(
        write(tmp_path, "# a pallet\nrows: 3\ncolumns: 2\nlayers: 2\nspacing: [0.08, 0.1]\nlayer_height: 0.05\n")
    )
    assert pattern == Pattern(3, 2, 2, (0.08, 0.1), 0.05)
    slots = pattern.slots(BOX)
    assert len(slots) == pattern.count == 12
    centre = [sum(s.x for s in slots) / 12, sum(s.y for s in slots) / 12]
    assert centre == pytest.approx([0.2, -0.3])
    assert math.dist((slots[0].x, slots[0].y), (slots[1].x, slots[1].y)) == pytest.approx(0.1)
    assert math.dist((slots[0].x, slots[0].y), (slots[2].x, slots[2].y)) == pytest.approx(0.08)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("rows: 2\n", "lacks columns"),
        ("rows: 2\ncolumns: 2\nlayer: 2\n", "unknown key(s) layer"),
        ("rows: 0\ncolumns: 2\n", "'rows' must be an integer >= 1, got 0"),
        ("rows: 2.5\ncolumns: 2\n", "'rows' must be an integer >= 1, got 2.5"),
        ("rows: 2\ncolumns: true\n", "'columns' must be an integer >= 1, got True"),
        ("rows: 2\ncolumns: 2\nlayers: 2\n", "with 2 layers needs 'layer_height'"),
        ("rows: 2\ncolumns: 2\nspacing: 0.1\n", "'spacing' must be [x, y] in metres, got 0.1"),
        ("rows: 2\ncolumns: 2\nspacing: [0.1, -0.1]\n", "'spacing' must be a length > 0 (m), got -0.1"),
        ("rows: 2\ncolumns: 2\nlayer_height: .nan\n", "'layer_height' must be a length > 0 (m), got nan"),
        ("[rows, columns]\n", "must be a mapping of rows, columns"),
        ("rows: [2\n", "is not valid YAML"),
    ],
)
def test_bad_pattern_files_are_named(tmp_path, text, message):
    with pytest.raises(PatternError, match="pattern file '.*pattern.yaml'") as raised:
        load_pattern(write(tmp_path, text))
    assert message in str(raised.value)


def test_the_example_pattern_fits_the_packing_worlds_box():
    pattern = load_pattern(PACKAGE / "examples/pallet_pattern.yaml")
    assert (pattern.rows, pattern.columns, pattern.layers) == (2, 3, 2)
    assert len(pattern.slots(BOX)) == 12


def test_a_grid_wider_than_the_box_is_refused(tmp_path):
    pattern = load_pattern(write(tmp_path, "rows: 4\ncolumns: 2\nspacing: [0.09, 0.1]\n"))
    with pytest.raises(PatternError, match=r"4 slots 0.09 m apart along x do not fit in box 'box' \(0.260 m"):
        pattern.slots(BOX)


@pytest.mark.parametrize("text", ["2by2", "0x2", "2x2x0", "2x", "x2"])
def test_bad_short_patterns(text):
    with pytest.raises(PatternError, match="pattern must be ROWSxCOLUMNS or ROWSxCOLUMNSxLAYERS"):
        parse_pattern(text)


def test_missing_file():
    with pytest.raises(PatternError, match="pattern file '/nonexistent.yaml': No such file"):
        load_pattern("/nonexistent.yaml")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("rows: 2\ncolumns: 2\nlayers: 2\n", "--pattern-file: pattern file"),
        ("rows: 2\ncolumns: x\n", "'columns' must be an integer >= 1, got 'x'"),
    ],
)
def test_pack_objects_refuses_a_bad_pattern_file_in_one_line(tmp_path, text, message):
    result = subprocess.run(
        [
            sys.executable,
            str(PACKAGE / "scripts/pack_objects.py"),
            "--box",
            "b",
            "--pattern-file",
            write(tmp_path, text),
        ],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 2
    assert message in result.stderr
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith("pack_objects.py: error: --pattern-file: pattern file")
