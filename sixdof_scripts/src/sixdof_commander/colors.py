"""Colour classes from the hue: how sixdof_perception names what the camera sees and sort_objects.py matches
objects to bins (sixdof_commander.sim_world)."""

from __future__ import annotations

import colorsys

# Hue ranges (degrees) of the colour classes; red wraps around 0.
HUE_CLASSES: tuple[tuple[str, float, float], ...] = (
    ("red", 345.0, 15.0),
    ("orange", 15.0, 40.0),
    ("yellow", 40.0, 70.0),
    ("green", 70.0, 170.0),
    ("cyan", 170.0, 200.0),
    ("blue", 200.0, 260.0),
    ("purple", 260.0, 345.0),
)
UNKNOWN_COLOR = "unknown"


def color_class(r: float, g: float, b: float, min_saturation: float = 0.3, min_value: float = 0.08) -> str:
    """Colour class of an RGB colour (components in [0, 1]) from its hue; 'unknown' for greys and black
    (the simulator's shading only darkens a surface, it keeps hue and saturation)."""
    for c in (r, g, b):
        if not (isinstance(c, int | float) and 0.0 <= c <= 1.0):
            raise ValueError(f"colour components must be numbers in [0, 1], got {(r, g, b)}")
    h, s, v = colorsys.rgb_to_hsv(r, g, b)
    if s < min_saturation or v < min_value:
        return UNKNOWN_COLOR
    hue = h * 360.0
    for name, low, high in HUE_CLASSES:
        if (low <= hue < high) if low < high else (hue >= low or hue < high):
            return name
    return UNKNOWN_COLOR
