"""Packing patterns: where the objects go in a box, in rows, columns and layers.

A pattern is `ROWSxCOLUMNS[xLAYERS]` (the box's inside cut into equal cells, `layer_height` apart) or a pallet-style
YAML file of these keys (every other key is an error):

    rows: 3              # slots along the box's x axis (an integer >= 1)
    columns: 2           # slots along its y axis (an integer >= 1)
    layers: 2            # optional, default 1: layers stacked on each other
    spacing: [0.08, 0.09]  # optional, m between neighbouring slot centres along x and y; default: the inside cut
                           # into equal cells. The grid is centred in the box and must fit inside its walls.
    layer_height: 0.06   # m from one layer's bottom to the next; required when layers > 1

Slots are filled layer by layer, each row by row. Bad input raises PatternError naming the problem.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import yaml

from .exceptions import SixdofCommanderError
from .sim_world import Bin

__all__ = ["Pattern", "PatternError", "Slot", "load_pattern", "parse_pattern"]

_SHORT = re.compile(r"^([1-9][0-9]*)x([1-9][0-9]*)(?:x([1-9][0-9]*))?$")
_KEYS = ("rows", "columns", "layers", "spacing", "layer_height")


class PatternError(SixdofCommanderError):
    """A pattern that cannot be used: the message names the key or value."""


@dataclass(frozen=True)
class Slot:
    """Where one object goes: world (x, y) of its centre and the height of its bottom above the box's floor."""

    x: float
    y: float
    bottom: float
    layer: int


@dataclass(frozen=True)
class Pattern:
    rows: int
    columns: int
    layers: int = 1
    spacing: tuple[float, float] | None = None  # None: equal cells filling the box's inside
    layer_height: float | None = None

    def __post_init__(self) -> None:
        for key in ("rows", "columns", "layers"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise PatternError(f"pattern '{key}' must be an integer >= 1, got {value!r}")
        if self.spacing is not None:
            if not isinstance(self.spacing, list | tuple) or len(self.spacing) != 2:
                raise PatternError(f"pattern 'spacing' must be [x, y] in metres, got {self.spacing!r}")
            for value in self.spacing:
                _check_length("spacing", value)
            object.__setattr__(self, "spacing", tuple(float(v) for v in self.spacing))
        if self.layer_height is not None:
            _check_length("layer_height", self.layer_height)
        elif self.layers > 1:
            raise PatternError(f"pattern with {self.layers} layers needs 'layer_height'")

    @property
    def count(self) -> int:
        return self.rows * self.columns * self.layers

    def slots(self, box: Bin) -> list[Slot]:
        """The slots in the box, in filling order; PatternError when the grid does not fit inside its walls."""
        hx, hy = box.inner_half()
        if self.spacing is None:
            dx, dy = 2.0 * hx / self.rows, 2.0 * hy / self.columns
        else:
            dx, dy = self.spacing
            for axis, step, n, half in (("x", dx, self.rows, hx), ("y", dy, self.columns, hy)):
                if (n - 1) * step > 2.0 * half + 1e-9:
                    raise PatternError(
                        f"pattern's {n} slots {step} m apart along {axis} do not fit in box '{box.name}' "
                        f"({2.0 * half:.3f} m between its walls)"
                    )
        height = self.layer_height or 0.0
        return [
            Slot(*box.to_world((r - (self.rows - 1) / 2.0) * dx, (c - (self.columns - 1) / 2.0) * dy), k * height, k)
            for k in range(self.layers)
            for r in range(self.rows)
            for c in range(self.columns)
        ]


def _check_length(key: str, value: object) -> None:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value <= 0.0:
        raise PatternError(f"pattern '{key}' must be a length > 0 (m), got {value!r}")


def parse_pattern(text: str, layer_height: float | None = None) -> Pattern:
    """`ROWSxCOLUMNS` or `ROWSxCOLUMNSxLAYERS` (equal cells; layers `layer_height` apart)."""
    match = _SHORT.match(text)
    if match is None:
        raise PatternError(f"pattern must be ROWSxCOLUMNS or ROWSxCOLUMNSxLAYERS (e.g. 2x2, 3x2x2), got '{text}'")
    layers = int(match.group(3) or 1)
    return Pattern(int(match.group(1)), int(match.group(2)), layers, None, layer_height if layers > 1 else None)


def load_pattern(path: str | Path) -> Pattern:
    """The pattern of a YAML file (module docstring)."""
    try:
        data = yaml.safe_load(Path(path).read_text())
    except OSError as err:
        raise PatternError(f"pattern file '{path}': {err.strerror}") from err
    except yaml.YAMLError as err:
        raise PatternError(f"pattern file '{path}' is not valid YAML: {str(err).splitlines()[0]}") from err
    if not isinstance(data, dict):
        raise PatternError(f"pattern file '{path}' must be a mapping of {', '.join(_KEYS)}")
    unknown = sorted(str(k) for k in data if k not in _KEYS)
    if unknown:
        raise PatternError(f"pattern file '{path}': unknown key(s) {', '.join(unknown)} (known: {', '.join(_KEYS)})")
    missing = [k for k in ("rows", "columns") if k not in data]
    if missing:
        raise PatternError(f"pattern file '{path}' lacks {', '.join(missing)}")
    try:
        return Pattern(**data)
    except PatternError as err:
        raise PatternError(f"pattern file '{path}': {err}") from err
