"""What the perception node and the sorting script know of the world besides the cloud (never the simulator's
object states): the tables' and conveyor belts' top faces (the supports), the static scenery (tables, belts, bin
walls), the bins with their colour classes and the cameras, all from the simulator's ~world parameter
(sixdof_commander.sim_world)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from sixdof_commander.sim_world import SimWorld, SimWorldError, WorldObject
from sixdof_commander.transforms import matrix_from_quaternion, rpy_from_quaternion

from .detection import Box, Support

__all__ = ["SimWorldError", "StaticBox", "static_boxes", "supports"]


@dataclass(frozen=True)
class StaticBox:
    """A static box of the scenery: name, centre, rotation (3x3), full size, and whether it is a table."""

    name: str
    centre: tuple[float, float, float]
    rotation: np.ndarray
    size: tuple[float, float, float]
    table: bool = False

    def as_mask(self) -> Box:
        return Box(np.asarray(self.centre), self.rotation, np.asarray(self.size) / 2.0)


def _is_support(obj: WorldObject) -> bool:
    """Tables and conveyor belts: objects rest on their top faces."""
    return obj.table or bool(obj.conveyor)


def supports(world: SimWorld) -> list[Support]:
    """The top faces of the world's tables and conveyor belts (yaw-only boxes)."""
    out = []
    for table in (o for o in world.objects if _is_support(o)):
        roll, pitch, yaw = rpy_from_quaternion(table.orientation)
        if abs(roll) > 1e-9 or abs(pitch) > 1e-9:
            raise SimWorldError(f"table '{table.name}': only yawed tables can be supports (roll and pitch must be 0)")
        x, y, z = table.position
        sx, sy, sz = table.size
        out.append(Support(z + sz / 2.0, (x, y), (sx / 2.0, sy / 2.0), yaw))
    return out


def _static_box(obj: WorldObject) -> StaticBox:
    return StaticBox(obj.name, obj.position, matrix_from_quaternion(obj.orientation), obj.size, obj.table)


def static_boxes(world: SimWorld) -> list[StaticBox]:
    """The static scenery as boxes: tables, and static box objects that collide (conveyor belts and bin walls among
    them: masked out of the cloud; a belt's top face is also a support)."""
    return [_static_box(o) for o in world.objects if o.table or (o.static and o.collision and o.shape == "box")]
