"""The packing world of a generated package (config/world_pack.yaml): the table, a conveyor belt across the arm's
front with a source upstream and a sink at its end, and an empty box on the table, placed where the arm reaches them
with its tool pointing down. Nothing is taken from a particular arm: the places are searched with the robot's own IK
(sixdof_core's bindings, the solver kinematics.yaml names), top-down tool poses at the heights a pick and a place
need, and the robot at its home state clear of the belt and the box (the core's collision scene).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import yaml

from . import templates
from .grasping import TCP_FRAME
from .infer import Plan

BELT_WIDTH = 0.16  # m across the belt
BELT_SPEED = 0.2  # m/s
# TCP heights checked above the belt's surface: at a 3 cm object's middle, and 5 cm above a 6 cm object.
PICK_HEIGHTS = (0.015, 0.11)
# m above the table: the belt heights tried, lowest first (an arm on a pedestal reaches down only so far); above the
# first, the box stands on a stand as high as the belt.
BELT_TOPS = (0.03, 0.1, 0.2, 0.3, 0.4)
BOX_SIDES = (0.28, 0.2)  # m: the box's sides tried, largest first (a small arm reaches round a small box only)
BOX_WALL, BOX_WALL_THICKNESS = 0.03, 0.01  # m
# TCP heights checked above the box's bottom: at a 3 cm object's middle, and over the wall with a 6 cm object held.
PLACE_HEIGHTS = (0.015, 0.12)
STEP = 0.02  # m between the points searched
UPSTREAM, DOWNSTREAM = 0.15, 0.1  # m of belt before and after the pick zone
MIN_ZONE = 0.1  # m: a shorter reachable stretch of belt is no pick zone
ZONE_HALF = 0.3  # m: the pick zone searched on either side of the arm's front


def top_down(x: float, y: float, z: float) -> np.ndarray:
    """The tool's pose at (x, y, z) pointing down (its z axis along -z), turned as the commander turns it: the wrist
    yaw that reaches the point without twisting (sixdof_commander.grasping.top_down_rotation, preferred_yaw)."""
    yaw = math.atan2(y, x) + math.pi
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([[cy, sy, 0.0, x], [sy, -cy, 0.0, y], [0.0, 0.0, -1.0, z], [0.0, 0.0, 0.0, 1.0]])


def slot_points(centre: tuple[float, float], side: float,
                thickness: float = BOX_WALL_THICKNESS) -> list[tuple[float, float]]:
    """The centres of the cells of a 2x2 and a 3x3 pattern in the box's inside (sixdof_commander.pack_pattern's
    equal cells)."""
    inside = side - 2.0 * thickness
    points = []
    for count in (2, 3):
        offsets = [inside * ((i + 0.5) / count - 0.5) for i in range(count)]
        points += [(centre[0] + dx, centre[1] + dy) for dx in offsets for dy in offsets]
    return points


class TopDownReach:
    """Whether the arm's tool reaches a point pointing down: IK of the arm group (the solver of kinematics.yaml) for
    the tip pose that puts the tool link (default: the tip) there. Deterministic: a fixed number of seeded starts, no
    time budget."""

    def __init__(self, model: Any, group: str, solver: str, tool_link: str, home: dict[str, float]) -> None:
        import sixdof_core  # noqa: PLC0415 (the compiled core, only when a packing world is made)

        self.core = sixdof_core
        chain = sixdof_core.KinematicChain.for_group(model, group)
        state = sixdof_core.RobotState(model)
        state.set_joint_positions(home)
        self.home = state
        self.tool_in_tip = np.linalg.inv(state.link_pose(chain.tip_link)) @ state.link_pose(tool_link or chain.tip_link)
        self.ik = sixdof_core.create_ik_solver(solver, model, group)
        self.options = sixdof_core.IkOptions(timeout=0.0, attempts=20, random_seed=1)
        self.scene = sixdof_core.CollisionScene(model)

    def reaches(self, x: float, y: float, z: float) -> bool:
        return bool(self.ik.solve(top_down(x, y, z) @ np.linalg.inv(self.tool_in_tip), self.options))

    def clear(self, boxes: list[tuple[list[float], list[float]]]) -> bool:
        """Whether the robot at home touches none of the boxes ((size, centre), axis-aligned; its own links may touch
        each other)."""
        self.scene.clear()
        for i, (size, centre) in enumerate(boxes):
            self.scene.add_box(f"box{i}", size, self.core.pose_from_xyz_rpy(*centre, 0.0, 0.0, 0.0))
        return not self.scene.is_colliding(self.home, self.core.CollisionScope.WORLD)


@dataclass
class Layout:
    belt_x: float  # the belt's centre line (world x), running towards +y
    belt_top: float  # its surface above the table
    zone: tuple[float, float]  # world y of the reachable stretch (the pick zone)
    box: tuple[float, float]  # the box's centre
    box_z: float  # the box's bottom (on the table, or on a stand that high)
    box_side: float

    @property
    def belt_y(self) -> tuple[float, float]:
        return self.zone[0] - UPSTREAM, self.zone[1] + DOWNSTREAM


def _zone(reach: TopDownReach, x: float, top: float) -> tuple[float, float] | None:
    """The stretch of belt at x (surface at top) around y = 0, within ZONE_HALF of it, where the tool reaches every
    pick height."""

    def ok(y: float) -> bool:
        return all(reach.reaches(x, y, top + h) for h in PICK_HEIGHTS)

    if not ok(0.0):
        return None
    ends = []
    for sign in (-1.0, 1.0):
        y = 0.0
        while abs(y) + STEP <= ZONE_HALF + 1e-9 and ok(y + sign * STEP):
            y += sign * STEP
        ends.append(y)
    return (ends[0], ends[1]) if ends[1] - ends[0] >= MIN_ZONE else None


def _box(reach: TopDownReach, belt_x: float, belt: Any, zone: tuple[float, float],
         z: float, side: float) -> tuple[float, float] | None:
    """The box's centre: beside the belt on the base's side of it, near the pick zone's upstream half, every slot
    reached at every place height, the robot at home clear of it."""
    near = belt_x - BELT_WIDTH / 2.0 - 0.03 - side / 2.0
    middle = (zone[0] + zone[1]) / 2.0
    for dy in np.arange(0.0, 2.0 * side, 2 * STEP):
        for x in np.arange(near, near - 2.0 * side, -2 * STEP):
            centre = (round(float(x), 3), round(float(middle - side / 2.0 - dy), 3))
            if not reach.clear([belt, ([side, side, z + BOX_WALL], [*centre, (z + BOX_WALL) / 2.0])]):
                continue
            if all(reach.reaches(px, py, z + h) for px, py in slot_points(centre, side) for h in PLACE_HEIGHTS):
                return centre
    return None


def find_layout(reach: TopDownReach, span: float) -> Layout | None:
    """The belt nearest the table with the longest pick zone (up to 2 x ZONE_HALF; of the distances from the base
    that give it, the middle one), and a box beside it; None when the tool reaches no stretch of belt pointing down.
    span: a bound on the arm's reach (m)."""
    for top in BELT_TOPS:
        found: list[tuple[float, tuple[float, float]]] = []
        for x in np.arange(STEP * 5, span, STEP):
            x = round(float(x), 3)
            belt = ([BELT_WIDTH, 2.0 * ZONE_HALF, top], [x, 0.0, top / 2.0])
            if reach.clear([belt]) and (zone := _zone(reach, x, top)):
                found.append((x, zone))
        if not found:
            continue
        longest = max(z[1] - z[0] for _, z in found)
        best = [(x, z) for x, z in found if z[1] - z[0] >= longest - 1e-9]
        x, zone = best[len(best) // 2]
        low, high = zone[0] - UPSTREAM, zone[1] + DOWNSTREAM
        belt = ([BELT_WIDTH, high - low, top], [x, (low + high) / 2.0, top / 2.0])
        box_z = 0.0 if top == BELT_TOPS[0] else top
        for side in BOX_SIDES:
            box = _box(reach, x, belt, zone, box_z, side)
            if box is not None:
                return Layout(belt_x=x, belt_top=top, zone=zone, box=box, box_z=box_z, box_side=side)
    return None


def _r(value: float) -> float:
    return round(float(value), 3)


def world_pack_yaml(robot: str, layout: Layout, header: str) -> str:
    """The world file: the table under the robot and its layout, the belt, its source and sinks, the box and a
    camera looking down into it (format: sixdof_sim/worlds/README.md)."""
    low, high = layout.belt_y
    length, centre_y = high - low, (low + high) / 2.0
    x_max = max(layout.belt_x + BELT_WIDTH / 2.0, layout.box[0] + layout.box_side / 2.0) + 0.15
    x_min = min(-0.3, layout.box[0] - layout.box_side / 2.0 - 0.1)
    y_max = max(abs(low), abs(high), abs(layout.box[1]) + layout.box_side / 2.0) + 0.1
    table = {"name": "table", "size": [_r(x_max - x_min), _r(2 * y_max), 0.75],
             "position": [_r((x_max + x_min) / 2), 0.0, -0.375], "friction": 0.8, "color": [0.55, 0.4, 0.25, 1.0]}
    top = layout.belt_top
    tables = [table]
    if layout.box_z > 0.0:
        tables.append({"name": "box_stand", "size": [layout.box_side, layout.box_side, _r(layout.box_z)],
                       "position": [*layout.box, _r(layout.box_z / 2)], "friction": 0.8, "color": [0.5, 0.5, 0.5, 1.0]})
    data = {
        "name": f"{robot}_packing", "gravity": [0.0, 0.0, -9.81], "ground": {"z": -0.75, "friction": 0.8},
        "tables": tables,
        "conveyors": [{"name": "belt", "size": [_r(length), BELT_WIDTH, top], "position": [
            layout.belt_x, _r(centre_y), _r(top / 2)], "rpy": [0.0, 0.0, math.pi / 2], "speed": BELT_SPEED,
            "friction": 0.8, "color": [0.15, 0.15, 0.17, 1.0]}],
        "sources": [{"name": "part", "conveyor": "belt", "position": [_r(0.05 - length / 2), 0.0],
                     "lateral_jitter": 0.02, "shapes": ["box", "cylinder"], "size": [0.03, 0.05],
                     "colors": [[0.9, 0.1, 0.1], [0.1, 0.7, 0.2], [0.1, 0.3, 0.9], [0.95, 0.85, 0.1]],
                     "mass": 0.05, "interval": [4.0, 6.0], "seed": 2}],
        "sinks": [{"name": "belt_end", "position": [layout.belt_x, _r(high + 0.1), _r(top)], "size": [0.4, 0.2, 0.2]},
                  {"name": "floor", "below": -0.7}],
        "bins": [{"name": "box", "color": [0.6, 0.45, 0.3], "position": [*layout.box, _r(layout.box_z)],
                  "size": [layout.box_side, layout.box_side], "wall_height": BOX_WALL,
                  "wall_thickness": BOX_WALL_THICKNESS}],
        "cameras": [{"name": "box_cam", "position": [*layout.box, _r(layout.box_z + 0.75)],
                     "rpy": [0.0, math.pi / 2, 0.0], "width": 640, "height": 480, "horizontal_fov_deg": 45, "rate": 2,
                     "near": 0.1, "far": 2.0}],
    }
    zone = (_r(layout.zone[0] - centre_y), _r(layout.zone[1] - centre_y))
    return (f"# {header}: the table, a belt across the arm's\n"
            f"# front running towards +y at {BELT_SPEED} m/s with a source upstream and sinks, an empty box beside\n"
            "# it and a camera over the box; placed where the tool reaches pointing down (by the robot's IK).\n"
            "# Format: sixdof_sim/worlds/README.md.\n"
            f"# pick zone: {zone[0]} to {zone[1]} m along the belt from its centre\n"
            + yaml.safe_dump(data, sort_keys=False, default_flow_style=None))


def packing_world(plan: Plan, report: dict[str, Any], urdf: str, srdf: str, search_roots: list[str]) -> str | None:
    """config/world_pack.yaml for the robot (its repaired URDF and generated SRDF text), None when its tool reaches
    no stretch of belt pointing down. The tool is the TCP link of a gripper or cup, else the arm's tip."""
    import sixdof_core  # noqa: PLC0415

    model = sixdof_core.RobotModel(urdf, srdf, search_roots=search_roots)
    arm = next(g for g in report["groups"] if g["name"] == plan.arm.name)
    tool = TCP_FRAME if templates.has_grasping(plan) and TCP_FRAME in model.link_names else ""
    home = next((values for _, group, values in plan.states if group == plan.arm.name), {})
    reach = TopDownReach(model, plan.arm.name, plan.arm.solver or arm["solver"], tool, home)
    layout = find_layout(reach, templates.span(report))
    return world_pack_yaml(plan.robot, layout, templates.HEADER) if layout else None


def pick_before(world_text: str) -> float:
    """pack_objects.py's --pick-before for a world_pack_yaml: the middle of its pick zone (the arm follows an object
    downstream while it picks it)."""
    zone = pick_zone(world_text)
    return _r((zone[0] + zone[1]) / 2.0)


def pick_zone(world_text: str) -> tuple[float, float]:
    """The pick zone a world_pack_yaml names in its header (m along the belt from its centre)."""
    for line in world_text.splitlines():
        if line.startswith("# pick zone: "):
            low, _, high = line.removeprefix("# pick zone: ").split()[:3]
            return float(low), float(high)
    raise ValueError("no '# pick zone:' line in the world file")


def readme_section(name: str, world_text: str | None) -> str:
    """The README's section on the packing world (or why there is none)."""
    if world_text is None:
        return ("\n## Packing world\n\nNo `config/world_pack.yaml`: the setup assistant found no belt in front of the "
                "arm and box beside it\nthat the tool reaches pointing down.\n")
    zone = pick_zone(world_text)
    side = yaml.safe_load(world_text)["bins"][0]["size"][0]
    return f"""
## Packing world

`config/world_pack.yaml` puts a conveyor belt across the arm's front (running towards +y at {BELT_SPEED} m/s, a
source dropping 3-5 cm boxes and cylinders onto its upstream end every 4-6 s, a sink at its end), an empty
{side * 100:g} cm box `box` on the table beside it and a camera `box_cam` looking down into the box. The setup
assistant placed them by the robot's IK: the tool reaches pointing down every point of the belt's pick zone
({zone[0]} to {zone[1]} m along the belt from its centre) from {PICK_HEIGHTS[0]} to {PICK_HEIGHTS[1]} m above it,
and the cells of a 2x2 and a 3x3 pattern in the box. Run the stack on it and pack:

    roslaunch {name} demo.launch world:=$(rospack find {name})/config/world_pack.yaml
    rosrun sixdof_scripts pack_objects.py --box box --pattern 2x2 --pick-before {pick_before(world_text)}
"""
