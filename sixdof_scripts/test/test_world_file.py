"""sixdof_commander.colors and world_file: colour classes, the world file's bins and non-colliding objects."""

import pytest
import yaml
from sixdof_commander.colors import color_class
from sixdof_commander.world_file import WorldFileError, bins, non_colliding_objects

WORLD = yaml.safe_load("""
bins:
  - {name: red_bin, color: [0.9, 0.1, 0.1], position: [0.2, 0.3, 0.0], size: [0.18, 0.12]}
  - {name: blue_bin, color: [0.1, 0.2, 0.9], position: [0.3, -0.3, 0.0], size: [0.2, 0.2], yaw: 1.5707963,
     wall_height: 0.05, wall_thickness: 0.02}
""")


def test_bins_have_colour_classes_and_walls_inside_the_footprint():
    red, blue = bins(WORLD)
    assert (red.name, red.color, blue.color) == ("red_bin", "red", "blue")
    assert red.contains(0.2, 0.3) and red.contains(0.27, 0.34)
    assert not red.contains(0.295, 0.3)  # inside the footprint, in the wall
    assert red.inner_half() == pytest.approx((0.08, 0.05))
    walls = {w.name: w for w in red.walls()}
    assert sorted(walls) == ["red_bin_wall_x_max", "red_bin_wall_x_min", "red_bin_wall_y_max", "red_bin_wall_y_min"]
    assert walls["red_bin_wall_x_min"].centre == pytest.approx((0.2 - 0.09 + 0.005, 0.3, 0.015))
    assert walls["red_bin_wall_x_min"].size == pytest.approx((0.01, 0.12, 0.03))
    assert walls["red_bin_wall_y_max"].size == pytest.approx((0.16, 0.01, 0.03))
    # Turned by 90 degrees: the bin's x axis is the world's y axis.
    x, y = blue.to_world(0.05, 0.0)
    assert (x, y) == pytest.approx((0.3, -0.25))


@pytest.mark.parametrize(
    ("entry", "message"),
    [
        ({"name": "b", "position": [0, 0, 0], "size": [0.1, 0.1]}, r"bins\[0\] \(b\): 'color'"),
        ({"name": "b", "color": [1, 0, 0], "size": [0.1, 0.1]}, r"bins\[0\] \(b\): 'position'"),
        ({"name": "b", "color": [1, 0, 0], "position": [0, 0, 0], "size": [0.1]}, r"'size' must be a list of 2"),
        ({"color": [1, 0, 0], "position": [0, 0, 0], "size": [0.1, 0.1]}, r"bins\[0\]: 'name'"),
    ],
)
def test_bad_bins_name_the_key(entry, message):
    with pytest.raises(WorldFileError, match=message):
        bins({"bins": [entry]})
    with pytest.raises(WorldFileError, match="'bins' must be a list"):
        bins({"bins": {"b": 1}})


def test_colour_classes():
    assert [color_class(*c) for c in ((0.9, 0.1, 0.1), (0.15, 0.75, 0.2), (0.1, 0.2, 0.9))] == ["red", "green", "blue"]
    assert color_class(0.6, 0.6, 0.6) == "unknown"
    with pytest.raises(ValueError, match="colour components"):
        color_class(0.5, -0.1, 0.0)


def test_non_colliding_objects_from_the_world_file():
    world = {"objects": [{"name": "cube"}, {"name": "marker", "collision": False}], "tables": [{"name": "table"}]}
    assert non_colliding_objects(world) == {"marker"}
    with pytest.raises(WorldFileError, match="objects"):
        non_colliding_objects({"objects": {"name": "x"}})
