"""sixdof_commander.colors and sim_world: colour classes, the simulator's ~world parameter read into bins,
objects and cameras, and a bad parameter named."""

import pytest
from sixdof_commander.colors import color_class
from sixdof_commander.sim_world import SimWorld, SimWorldError


def box(name: str, **flags) -> dict:
    entry = {
        "name": name,
        "shape": "box",
        "size": [0.1, 0.1, 0.1],
        "position": [0.4, 0.0, 0.05],
        "orientation": [0.0, 0.0, 0.0, 1.0],
        "static": False,
        "collision": True,
        "table": False,
        "bin": "",
        "conveyor": "",
        "color": [0.7, 0.7, 0.7, 1.0],
    }
    entry.update(flags)
    return entry


BIN = {
    "name": "blue_bin",
    "color": [0.1, 0.2, 0.9, 1.0],
    "position": [0.3, -0.3, 0.0],
    "yaw": 1.5707963,
    "size": [0.2, 0.18],
    "wall_height": 0.05,
    "wall_thickness": 0.02,
}
WORLD = {
    "name": "w",
    "objects": [
        box("table", static=True, table=True),
        box("marker", static=True, collision=False),
        {**{k: v for k, v in box("ball").items() if k != "size"}, "shape": "sphere", "radius": 0.02},
    ],
    "bins": [BIN],
    "cameras": [{"name": "table_cam", "parent_link": ""}],
    "conveyors": [
        {
            "name": "belt",
            "size": [1.0, 0.16, 0.03],
            "position": [0.45, 0.0, 0.015],
            "orientation": [0.0, 0.0, 0.7071068, 0.7071068],
            "speed": 0.1,
            "direction": [0.0, 1.0, 0.0],
            "friction": 0.8,
        }
    ],
}


def test_world_from_the_parameter():
    world = SimWorld.from_parameter(WORLD)
    assert world.name == "w" and world.cameras == ("table_cam",)
    assert world.non_colliding() == {"marker"}
    table, _, ball = world.objects
    assert table.table and table.static and table.size == (0.1, 0.1, 0.1)
    assert ball.shape == "sphere" and ball.size is None
    (blue,) = world.bins
    assert (blue.name, blue.color) == ("blue_bin", "blue")
    assert blue.rgb == pytest.approx((0.1, 0.2, 0.9))
    assert blue.inner_half() == pytest.approx((0.08, 0.07))
    # Turned by 90 degrees: the bin's x axis is the world's y axis.
    assert blue.to_world(0.05, 0.0) == pytest.approx((0.3, -0.25))
    assert blue.contains(0.3, -0.3) and not blue.contains(0.3, -0.395)
    (belt,) = world.conveyors
    assert (belt.name, belt.speed, belt.direction) == ("belt", 0.1, (0.0, 1.0, 0.0))


@pytest.mark.parametrize(
    ("world", "message"),
    [
        ([], r"sixdof_sim/world: must be a mapping"),
        ({**WORLD, "bins": [{**BIN, "yaw": "x"}]}, r"bins\[0\]: 'yaw' has the wrong type"),
        ({**WORLD, "bins": [{k: v for k, v in BIN.items() if k != "size"}]}, r"bins\[0\]: 'size' is missing"),
        ({**WORLD, "objects": [box("t", position=[0, 0])]}, r"objects\[0\]: 'position' must be a list of 3"),
        ({**WORLD, "objects": [box("t", table=1)]}, r"objects\[0\]: 'table' has the wrong type"),
        ({k: v for k, v in WORLD.items() if k != "cameras"}, r"'cameras' is missing"),
        ({k: v for k, v in WORLD.items() if k != "conveyors"}, r"'conveyors' is missing"),
        ({**WORLD, "conveyors": [{"name": "belt"}]}, r"conveyors\[0\]: 'size' is missing"),
        ({**WORLD, "objects": [{k: v for k, v in box("t").items() if k != "conveyor"}]}, r"'conveyor' is missing"),
    ],
)
def test_a_bad_parameter_names_the_key(world, message):
    with pytest.raises(SimWorldError, match=message):
        SimWorld.from_parameter(world)


def test_colour_classes():
    assert [color_class(*c) for c in ((0.9, 0.1, 0.1), (0.15, 0.75, 0.2), (0.1, 0.2, 0.9))] == ["red", "green", "blue"]
    assert color_class(0.6, 0.6, 0.6) == "unknown"
    with pytest.raises(ValueError, match="colour components"):
        color_class(0.5, -0.1, 0.0)
