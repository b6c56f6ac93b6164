"""What Python reads of a simulator world file (sixdof_sim/worlds/README.md): the bins of its bins: section with
their colour classes, and the objects declared without collision. Used by sort_objects.py, scene_mirror
(sixdof_bringup) and sixdof_perception."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import NamedTuple

from .colors import color_class

# Defaults of the world file's bins: section (sixdof_sim/worlds/README.md#bins, world_file.cpp).
BIN_WALL_HEIGHT = 0.03
BIN_WALL_THICKNESS = 0.01


class WorldFileError(ValueError):
    """A world file this module cannot use; the message names the key."""


class Wall(NamedTuple):
    """One wall of a bin: name, centre, yaw about z, full size."""

    name: str
    centre: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]


@dataclass(frozen=True)
class Bin:
    name: str
    color: str  # colour class of the bin's colour
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

    def walls(self) -> list[Wall]:
        """The four walls, as the simulator builds them (sixdof_sim's world_file.cpp)."""
        hx, hy, t, h = self.size[0] / 2.0, self.size[1] / 2.0, self.wall_thickness, self.wall_height
        sides = [
            ("x_min", (-hx + t / 2, 0.0), (t, self.size[1])),
            ("x_max", (hx - t / 2, 0.0), (t, self.size[1])),
            ("y_min", (0.0, -hy + t / 2), (self.size[0] - 2 * t, t)),
            ("y_max", (0.0, hy - t / 2), (self.size[0] - 2 * t, t)),
        ]
        out = []
        for suffix, (u, v), (sx, sy) in sides:
            x, y = self.to_world(u, v)
            out.append(Wall(f"{self.name}_wall_{suffix}", (x, y, self.centre[2] + h / 2), self.yaw, (sx, sy, h)))
        return out


def world_numbers(entry: Mapping, key: str, count: int, where: str, default: list | None = None) -> list[float]:
    value = entry.get(key, default)
    if (
        not isinstance(value, list)
        or len(value) != count
        or not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in value)
    ):
        raise WorldFileError(f"{where}: '{key}' must be a list of {count} numbers")
    return [float(v) for v in value]


def world_list(world: Mapping, key: str) -> list:
    entries = world.get(key) or []
    if not isinstance(entries, list):
        raise WorldFileError(f"world file: '{key}' must be a list")
    for i, entry in enumerate(entries):
        if not isinstance(entry, Mapping):
            raise WorldFileError(f"world file: {key}[{i}] must be a mapping")
    return entries


def check_world(world: object) -> Mapping:
    if not isinstance(world, Mapping):
        raise WorldFileError("world file must be a YAML mapping")
    return world


def bins(world: Mapping) -> list[Bin]:
    """The world's bins with their colour classes."""
    out = []
    for i, entry in enumerate(world_list(check_world(world), "bins")):
        where = f"bins[{i}]"
        name = entry.get("name")
        if not isinstance(name, str) or not name:
            raise WorldFileError(f"{where}: 'name' must be a non-empty string")
        color = entry.get("color")
        if not isinstance(color, list) or len(color) not in (3, 4):
            raise WorldFileError(f"{where} ({name}): 'color' must be [r, g, b] or [r, g, b, a]")
        rgb = world_numbers({"color": color[:3]}, "color", 3, f"{where} ({name})")
        position = world_numbers(entry, "position", 3, f"{where} ({name})")
        size = world_numbers(entry, "size", 2, f"{where} ({name})")
        yaw = entry.get("yaw", 0.0)
        height = entry.get("wall_height", BIN_WALL_HEIGHT)
        thickness = entry.get("wall_thickness", BIN_WALL_THICKNESS)
        try:
            out.append(
                Bin(name, color_class(*rgb), tuple(position), float(yaw), tuple(size), float(height), float(thickness))
            )
        except (TypeError, ValueError) as err:
            raise WorldFileError(f"{where} ({name}): {err}") from err
    return out


def non_colliding_objects(world: Mapping) -> set[str]:
    """Names of the world file's objects declared `collision: false` (visual markers: never mirrored)."""
    names = set()
    for key in ("objects", "tables"):
        for entry in world_list(check_world(world), key):
            if entry.get("collision", True) is False:
                names.add(str(entry.get("name")))
    return names
