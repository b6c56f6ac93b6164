"""What the perception node and the sorting script know from the world file (never from the simulator's
object states): the tables' top faces (the supports), the static scenery (tables, static objects, the bins'
walls) and the bins with their colour classes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from sixdof_commander.transforms import matrix_from_rpy
from sixdof_commander.world_file import (
    WorldFileError,
    bins,
    check_world,
    world_list,
    world_numbers,
)

from .detection import Box, Support

__all__ = ["WorldFileError", "bins", "camera_names", "static_boxes", "supports"]


@dataclass(frozen=True)
class StaticBox:
    """A static box of the scenery: name, centre, yaw-only or full rotation (3x3), full size."""

    name: str
    centre: tuple[float, float, float]
    rotation: np.ndarray
    size: tuple[float, float, float]

    def as_mask(self) -> Box:
        return Box(np.asarray(self.centre), self.rotation, np.asarray(self.size) / 2.0)


def supports(world: Mapping) -> list[Support]:
    """The top faces of the world's tables (yaw-only tables)."""
    out = []
    for i, table in enumerate(world_list(check_world(world), "tables")):
        where = f"tables[{i}]"
        size = world_numbers(table, "size", 3, where)
        position = world_numbers(table, "position", 3, where)
        roll, pitch, yaw = world_numbers(table, "rpy", 3, where, [0.0, 0.0, 0.0])
        if abs(roll) > 1e-9 or abs(pitch) > 1e-9:
            raise WorldFileError(f"{where}: only yawed tables can be supports (rpy roll and pitch must be 0)")
        out.append(
            Support(position[2] + size[2] / 2.0, (position[0], position[1]), (size[0] / 2.0, size[1] / 2.0), yaw)
        )
    return out


def _static_box(entry: Mapping, where: str) -> StaticBox:
    return StaticBox(
        str(entry.get("name")),
        tuple(world_numbers(entry, "position", 3, where)),
        matrix_from_rpy(*world_numbers(entry, "rpy", 3, where, [0.0, 0.0, 0.0])),
        tuple(world_numbers(entry, "size", 3, where)),
    )


def static_boxes(world: Mapping) -> list[StaticBox]:
    """The static scenery as boxes: tables, static box objects that collide, the bins' walls."""
    world = check_world(world)
    out = [_static_box(table, f"tables[{i}]") for i, table in enumerate(world_list(world, "tables"))]
    for i, obj in enumerate(world_list(world, "objects")):
        if obj.get("static", False) is True and obj.get("collision", True) is not False and obj.get("shape") == "box":
            out.append(_static_box(obj, f"objects[{i}]"))
    for b in bins(world):
        out.extend(
            StaticBox(wall.name, wall.centre, matrix_from_rpy(0.0, 0.0, wall.yaw), wall.size) for wall in b.walls()
        )
    return out


def camera_names(world: Mapping) -> list[str]:
    return [str(c.get("name")) for c in world_list(check_world(world), "cameras")]
