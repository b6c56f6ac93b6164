"""What the perception node and the sorting script know from the world file (never from the simulator's
object states): the tables' top faces (the supports), the static scenery (tables, static objects, the bins'
walls) and the bins with their colour classes."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from .detection import Box, Support, color_class

# Defaults of the world file's bins: section (sixdof_sim/worlds/README.md#bins, world_file.cpp).
BIN_WALL_HEIGHT = 0.03
BIN_WALL_THICKNESS = 0.01


class WorldFileError(ValueError):
    """A world file this module cannot use; the message names the key."""


@dataclass(frozen=True)
class StaticBox:
    """A static box of the scenery: name, centre, yaw-only or full rotation (3x3), full size."""

    name: str
    centre: tuple[float, float, float]
    rotation: np.ndarray
    size: tuple[float, float, float]

    def as_mask(self) -> Box:
        return Box(np.asarray(self.centre), self.rotation, np.asarray(self.size) / 2.0)


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

    def walls(self) -> list[StaticBox]:
        """The four walls, as the simulator builds them (world_file.cpp)."""
        hx, hy, t, h = self.size[0] / 2.0, self.size[1] / 2.0, self.wall_thickness, self.wall_height
        sides = [
            ("x_min", (-hx + t / 2, 0.0), (t, self.size[1])),
            ("x_max", (hx - t / 2, 0.0), (t, self.size[1])),
            ("y_min", (0.0, -hy + t / 2), (self.size[0] - 2 * t, t)),
            ("y_max", (0.0, hy - t / 2), (self.size[0] - 2 * t, t)),
        ]
        rotation = rotation_rpy(0.0, 0.0, self.yaw)
        out = []
        for suffix, (u, v), (sx, sy) in sides:
            x, y = self.to_world(u, v)
            out.append(StaticBox(f"{self.name}_wall_{suffix}", (x, y, self.centre[2] + h / 2), rotation, (sx, sy, h)))
        return out


def rotation_rpy(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (URDF / the world file's rpy)."""
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def _numbers(entry: Mapping, key: str, count: int, where: str, default: list | None = None) -> list[float]:
    value = entry.get(key, default)
    if (
        not isinstance(value, list)
        or len(value) != count
        or not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in value)
    ):
        raise WorldFileError(f"{where}: '{key}' must be a list of {count} numbers")
    return [float(v) for v in value]


def _list(world: Mapping, key: str) -> list:
    entries = world.get(key) or []
    if not isinstance(entries, list):
        raise WorldFileError(f"world file: '{key}' must be a list")
    for i, entry in enumerate(entries):
        if not isinstance(entry, Mapping):
            raise WorldFileError(f"world file: {key}[{i}] must be a mapping")
    return entries


def _check_world(world: object) -> Mapping:
    if not isinstance(world, Mapping):
        raise WorldFileError("world file must be a YAML mapping")
    return world


def supports(world: Mapping) -> list[Support]:
    """The top faces of the world's tables (yaw-only tables)."""
    out = []
    for i, table in enumerate(_list(_check_world(world), "tables")):
        where = f"tables[{i}]"
        size = _numbers(table, "size", 3, where)
        position = _numbers(table, "position", 3, where)
        roll, pitch, yaw = _numbers(table, "rpy", 3, where, [0.0, 0.0, 0.0])
        if abs(roll) > 1e-9 or abs(pitch) > 1e-9:
            raise WorldFileError(f"{where}: only yawed tables can be supports (rpy roll and pitch must be 0)")
        out.append(
            Support(position[2] + size[2] / 2.0, (position[0], position[1]), (size[0] / 2.0, size[1] / 2.0), yaw)
        )
    return out


def bins(world: Mapping) -> list[Bin]:
    """The world's bins with their colour classes."""
    out = []
    for i, entry in enumerate(_list(_check_world(world), "bins")):
        where = f"bins[{i}]"
        name = entry.get("name")
        if not isinstance(name, str) or not name:
            raise WorldFileError(f"{where}: 'name' must be a non-empty string")
        color = entry.get("color")
        if not isinstance(color, list) or len(color) not in (3, 4):
            raise WorldFileError(f"{where} ({name}): 'color' must be [r, g, b] or [r, g, b, a]")
        rgb = _numbers({"color": color[:3]}, "color", 3, f"{where} ({name})")
        position = _numbers(entry, "position", 3, f"{where} ({name})")
        size = _numbers(entry, "size", 2, f"{where} ({name})")
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


def _static_box(entry: Mapping, where: str) -> StaticBox:
    return StaticBox(
        str(entry.get("name")),
        tuple(_numbers(entry, "position", 3, where)),
        rotation_rpy(*_numbers(entry, "rpy", 3, where, [0.0, 0.0, 0.0])),
        tuple(_numbers(entry, "size", 3, where)),
    )


def static_boxes(world: Mapping) -> list[StaticBox]:
    """The static scenery as boxes: tables, static box objects that collide, the bins' walls."""
    world = _check_world(world)
    out = [_static_box(table, f"tables[{i}]") for i, table in enumerate(_list(world, "tables"))]
    for i, obj in enumerate(_list(world, "objects")):
        if obj.get("static", False) is True and obj.get("collision", True) is not False and obj.get("shape") == "box":
            out.append(_static_box(obj, f"objects[{i}]"))
    for b in bins(world):
        out.extend(b.walls())
    return out


def camera_names(world: Mapping) -> list[str]:
    return [str(c.get("name")) for c in _list(_check_world(world), "cameras")]
