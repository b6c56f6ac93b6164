"""The simulator's world as it loaded it: the sixdof_sim node's ~world parameter (sixdof_sim/worlds/README.md,
"The ~world parameter"), with every default of the world file applied. The world file is parsed by the
simulator only; sort_objects.py, scene_mirror (sixdof_bringup) and sixdof_perception read this."""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass

import rospy

from .colors import color_class

WORLD_PARAMETER = "sixdof_sim/world"


class SimWorldError(ValueError):
    """A ~world parameter this module cannot use, or none; the message names the parameter and the key."""


@dataclass(frozen=True)
class WorldObject:
    """An object the world file declared (a table, an object or a bin's wall), as the simulator built it."""

    name: str
    shape: str  # box, cylinder, sphere or mesh
    position: tuple[float, float, float]  # of the shape's centre
    orientation: tuple[float, float, float, float]  # x, y, z, w
    size: tuple[float, float, float] | None  # box: full size
    static: bool
    collision: bool
    table: bool  # declared under tables:
    bin: str  # the bin this is a wall of; '' when none
    conveyor: str = ""  # the conveyor this is the belt of; '' when none


@dataclass(frozen=True)
class Bin:
    name: str
    color: str  # colour class of the bin's colour
    rgb: tuple[float, float, float]
    centre: tuple[float, float, float]  # bottom centre
    yaw: float
    size: tuple[float, float]  # outer footprint
    wall_height: float
    wall_thickness: float

    def inner_half(self) -> tuple[float, float]:
        return (self.size[0] / 2.0 - self.wall_thickness, self.size[1] / 2.0 - self.wall_thickness)

    def to_local(self, x: float, y: float) -> tuple[float, float]:
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        dx, dy = x - self.centre[0], y - self.centre[1]
        return dx * c + dy * s, -dx * s + dy * c

    def to_world(self, u: float, v: float) -> tuple[float, float]:
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return self.centre[0] + u * c - v * s, self.centre[1] + u * s + v * c

    def contains(self, x: float, y: float) -> bool:
        """(x, y) inside the walls."""
        u, v = self.to_local(x, y)
        hx, hy = self.inner_half()
        return abs(u) < hx and abs(v) < hy


@dataclass(frozen=True)
class Conveyor:
    """A conveyor of the world file: its belt is the top face of a static box (also among the objects)."""

    name: str
    size: tuple[float, float, float]  # x along the conveyor, y across, z thick
    position: tuple[float, float, float]  # of the box centre
    orientation: tuple[float, float, float, float]  # x, y, z, w
    speed: float  # m/s, the world file's (sixdof_sim/set_conveyor changes it; conveyor_states has the current one)
    direction: tuple[float, float, float]  # unit, world frame: the belt moves objects along it at `speed`
    friction: float


@dataclass(frozen=True)
class SimWorld:
    name: str
    objects: tuple[WorldObject, ...]
    bins: tuple[Bin, ...]
    cameras: tuple[str, ...]
    conveyors: tuple[Conveyor, ...] = ()

    def non_colliding(self) -> set[str]:
        """Names of the objects declared `collision: false` (visual markers)."""
        return {o.name for o in self.objects if not o.collision}

    @classmethod
    def from_parameter(cls, value: object, where: str = WORLD_PARAMETER) -> SimWorld:
        """The world from the parameter's value; SimWorldError names a missing or ill-typed key."""
        reader = _Reader(where)
        world = reader.mapping(value, "")
        objects = tuple(_object(reader, e, f"objects[{i}]") for i, e in enumerate(reader.items(world, "objects")))
        bins = tuple(_bin(reader, e, f"bins[{i}]") for i, e in enumerate(reader.items(world, "bins")))
        cameras = tuple(reader.text(e, f"cameras[{i}]", "name") for i, e in enumerate(reader.items(world, "cameras")))
        conveyors = tuple(
            _conveyor(reader, e, f"conveyors[{i}]") for i, e in enumerate(reader.items(world, "conveyors"))
        )
        return cls(reader.text(world, "", "name"), objects, bins, cameras, conveyors)


def wait_for_world(parameter: str = WORLD_PARAMETER, timeout: float = 60.0) -> SimWorld:
    """The world once the simulator has set its parameter (waits up to timeout wall-clock seconds)."""
    name = rospy.resolve_name(parameter)
    deadline = time.monotonic() + timeout
    while not rospy.has_param(name):
        if rospy.is_shutdown() or time.monotonic() > deadline:
            raise SimWorldError(f"{name}: no such parameter after {timeout:g} s (is the sixdof_sim node running?)")
        time.sleep(0.1)
    return SimWorld.from_parameter(rospy.get_param(name), name)


class _Reader:
    def __init__(self, where: str) -> None:
        self.where = where

    def fail(self, context: str, problem: str) -> SimWorldError:
        return SimWorldError(f"{self.where}: {context + ': ' if context else ''}{problem}")

    def mapping(self, value: object, context: str) -> Mapping:
        if not isinstance(value, Mapping):
            raise self.fail(context, "must be a mapping")
        return value

    def get(self, entry: Mapping, context: str, key: str, kind: type | tuple[type, ...]) -> object:
        if key not in entry:
            raise self.fail(context, f"'{key}' is missing")
        value = entry[key]
        if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
            raise self.fail(context, f"'{key}' has the wrong type")
        return value

    def text(self, entry: Mapping, context: str, key: str) -> str:
        return str(self.get(entry, context, key, str))

    def flag(self, entry: Mapping, context: str, key: str) -> bool:
        return bool(self.get(entry, context, key, bool))

    def number(self, entry: Mapping, context: str, key: str) -> float:
        return float(self.get(entry, context, key, (int, float)))

    def numbers(self, entry: Mapping, context: str, key: str, count: int) -> tuple[float, ...]:
        value = self.get(entry, context, key, list)
        if len(value) != count or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in value):
            raise self.fail(context, f"'{key}' must be a list of {count} numbers")
        return tuple(float(v) for v in value)

    def items(self, world: Mapping, key: str) -> list[Mapping]:
        return [self.mapping(entry, f"{key}[{i}]") for i, entry in enumerate(self.get(world, "", key, list))]


def _object(reader: _Reader, entry: Mapping, context: str) -> WorldObject:
    shape = reader.text(entry, context, "shape")
    return WorldObject(
        name=reader.text(entry, context, "name"),
        shape=shape,
        position=reader.numbers(entry, context, "position", 3),
        orientation=reader.numbers(entry, context, "orientation", 4),
        size=reader.numbers(entry, context, "size", 3) if shape == "box" else None,
        static=reader.flag(entry, context, "static"),
        collision=reader.flag(entry, context, "collision"),
        table=reader.flag(entry, context, "table"),
        bin=reader.text(entry, context, "bin"),
        conveyor=reader.text(entry, context, "conveyor"),
    )


def _conveyor(reader: _Reader, entry: Mapping, context: str) -> Conveyor:
    return Conveyor(
        name=reader.text(entry, context, "name"),
        size=reader.numbers(entry, context, "size", 3),
        position=reader.numbers(entry, context, "position", 3),
        orientation=reader.numbers(entry, context, "orientation", 4),
        speed=reader.number(entry, context, "speed"),
        direction=reader.numbers(entry, context, "direction", 3),
        friction=reader.number(entry, context, "friction"),
    )


def _bin(reader: _Reader, entry: Mapping, context: str) -> Bin:
    r, g, b, _ = reader.numbers(entry, context, "color", 4)
    size = reader.numbers(entry, context, "size", 2)
    return Bin(
        name=reader.text(entry, context, "name"),
        color=color_class(r, g, b),
        rgb=(r, g, b),
        centre=reader.numbers(entry, context, "position", 3),
        yaw=reader.number(entry, context, "yaw"),
        size=(size[0], size[1]),
        wall_height=reader.number(entry, context, "wall_height"),
        wall_thickness=reader.number(entry, context, "wall_thickness"),
    )
