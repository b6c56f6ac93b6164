"""Parametric solids of the sixdof arm's links, built with trimesh + manifold3d (CSG).

Every builder returns a watertight trimesh.Trimesh in the link's own frame (the URDF link frame at zero
joint values). `fine` selects the visual resolution; the coarse version feeds the collision hulls.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import manifold3d
import numpy as np
import trimesh

# Coordinates are rounded before export so tiny floating-point differences between machines do not
# change the committed files.
QUANTUM_DECIMALS = 6


@dataclass(frozen=True)
class Resolution:
    segments: int
    fillet_segments: int
    rounded: bool


class DesignError(ValueError):
    """A design parameter is missing or makes an impossible solid."""


def _rotation_to(axis: str) -> np.ndarray:
    """Homogeneous rotation taking the +z axis onto the named axis."""
    if axis == "z":
        return np.eye(4)
    if axis == "y":
        return trimesh.transformations.rotation_matrix(-math.pi / 2.0, [1.0, 0.0, 0.0])
    if axis == "x":
        return trimesh.transformations.rotation_matrix(math.pi / 2.0, [0.0, 1.0, 0.0])
    raise DesignError(f"unknown axis '{axis}'")


def _translation(xyz: Sequence[float]) -> np.ndarray:
    return trimesh.transformations.translation_matrix(np.asarray(xyz, dtype=float))



def _ring_profile(radius: float, lo: float, hi: float, f: float, res: Resolution) -> list[tuple[float, float]]:
    """Outer (radius, z) profile of a ring from lo to hi, its two edges rounded with fillet radius f (0: sharp)."""
    if f <= 0.0:
        return [(radius, lo), (radius, hi)]
    profile = []
    for k in range(res.fillet_segments + 1):
        a = -math.pi / 2.0 + (math.pi / 2.0) * k / res.fillet_segments
        profile.append((radius - f + f * math.cos(a), lo + f + f * math.sin(a)))
    for k in range(res.fillet_segments + 1):
        a = (math.pi / 2.0) * k / res.fillet_segments
        profile.append((radius - f + f * math.cos(a), hi - f + f * math.sin(a)))
    return profile

def rounded_cylinder(
    radius: float, span: Sequence[float], axis: str, centre: Sequence[float], fillet: float, res: Resolution
) -> trimesh.Trimesh:
    """Cylinder around `axis` through `centre`, from span[0] to span[1] along the axis, edges rounded."""
    lo, hi = float(span[0]), float(span[1])
    length = hi - lo
    if radius <= 0.0 or length <= 0.0:
        raise DesignError(f"cylinder needs a positive radius and span, got r={radius}, span={span}")
    f = min(fillet, 0.45 * radius, 0.45 * length) if res.rounded else 0.0
    profile = [(0.0, lo), *_ring_profile(radius, lo, hi, f, res), (0.0, hi)]
    mesh = trimesh.creation.revolve(np.asarray(profile), sections=res.segments)
    mesh.apply_transform(_translation(centre) @ _rotation_to(axis))
    return mesh


def rounded_box(lo: Sequence[float], hi: Sequence[float], fillet: float, res: Resolution) -> trimesh.Trimesh:
    """Axis-aligned box between corners lo and hi with rounded edges (hull of corner spheres)."""
    lo_a, hi_a = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    size = hi_a - lo_a
    if np.any(size <= 0.0):
        raise DesignError(f"box needs hi > lo, got lo={list(lo)}, hi={list(hi)}")
    f = min(fillet, 0.45 * float(size.min())) if res.rounded else 0.0
    if f <= 0.0:
        box = trimesh.creation.box(extents=size)
        box.apply_translation((lo_a + hi_a) / 2.0)
        return box
    sphere = _sphere_points(f, res.fillet_segments)
    points = []
    for cx in (lo_a[0] + f, hi_a[0] - f):
        for cy in (lo_a[1] + f, hi_a[1] - f):
            for cz in (lo_a[2] + f, hi_a[2] - f):
                points.append(sphere + np.array([cx, cy, cz]))
    return hull(np.vstack(points))


def _sphere_points(radius: float, quarter_segments: int) -> np.ndarray:
    """Points of a UV sphere that include the six axis extremes, so rounded boxes keep their exact size."""
    lat = np.linspace(0.0, math.pi, 2 * quarter_segments + 1)
    lon = np.arange(4 * quarter_segments) * (2.0 * math.pi / (4 * quarter_segments))
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    points = np.column_stack([(np.sin(lat_g) * np.cos(lon_g)).ravel(), (np.sin(lat_g) * np.sin(lon_g)).ravel(),
                              np.cos(lat_g).ravel()])
    return radius * points


def hull(points_or_meshes) -> trimesh.Trimesh:
    """Convex hull of points or of several meshes together."""
    if isinstance(points_or_meshes, np.ndarray):
        points = points_or_meshes
    else:
        points = np.vstack([m.vertices for m in points_or_meshes])
    return trimesh.convex.convex_hull(np.round(points, 9))


def to_manifold(mesh: trimesh.Trimesh) -> manifold3d.Manifold:
    """The mesh as a manifold3d solid (double precision); DesignError if it is not a closed manifold."""
    solid = manifold3d.Manifold(
        mesh=manifold3d.Mesh64(vert_properties=np.array(mesh.vertices.view(np.ndarray), dtype=np.float64, order="C"),
                               tri_verts=np.array(mesh.faces.view(np.ndarray), dtype=np.uint64, order="C")))
    if solid.status() != manifold3d.Error.NoError:
        raise DesignError(f"a CSG operand is not a closed manifold solid ({solid.status()})")
    return solid


def _trimesh(solid: manifold3d.Manifold) -> trimesh.Trimesh:
    # process=False keeps manifold's vertex indexing: merging coincident vertices by position could pinch
    # edges where two operands touch.
    out = solid.to_mesh64()
    return trimesh.Trimesh(vertices=np.asarray(out.vert_properties)[:, :3], faces=np.asarray(out.tri_verts),
                           process=False)


def union(meshes: Sequence[trimesh.Trimesh]) -> trimesh.Trimesh:
    return _trimesh(manifold3d.Manifold.batch_boolean([to_manifold(m) for m in meshes], manifold3d.OpType.Add))


def difference(a: trimesh.Trimesh, b: Sequence[trimesh.Trimesh]) -> trimesh.Trimesh:
    cutter = manifold3d.Manifold.batch_boolean([to_manifold(m) for m in b], manifold3d.OpType.Add)
    return _trimesh(to_manifold(a) - cutter)


def quantize(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Round vertices so the exported files do not depend on the last bits of floating point."""
    return trimesh.Trimesh(vertices=np.round(mesh.vertices, QUANTUM_DECIMALS), faces=mesh.faces, process=False)


# --- link builders --------------------------------------------------------------------------------


def _cyl(p: dict, key_r: str, span, axis: str, centre, res: Resolution, fillet: float | None = None):
    return rounded_cylinder(p[key_r], span, axis, centre, p["fillet"] if fillet is None else fillet, res)


def revolved_stack(rings: Sequence[tuple[float, float, float, float]], res: Resolution) -> trimesh.Trimesh:
    """One solid of revolution about z from stacked (radius, z_lo, z_hi, fillet) rings, bottom to top.

    A single profile avoids coincident faces between coaxial parts (they would make CSG output non-manifold).
    """
    profile = [(0.0, rings[0][1])]
    for radius, lo, hi, fillet in rings:
        f = min(fillet, 0.45 * (hi - lo)) if res.rounded else 0.0
        profile += _ring_profile(radius, lo, hi, f, res)
    profile.append((0.0, rings[-1][2]))
    return trimesh.creation.revolve(np.asarray(profile), sections=res.segments)


def base_link(p: dict, joint1_z: float, res: Resolution) -> trimesh.Trimesh:
    top = joint1_z - 0.002
    solid = revolved_stack([
        (p["flange_r"], 0.0, p["flange_t"], p["fillet"] / 2.0),
        (p["body_r"], p["flange_t"], top - p["cap_t"], 0.0),
        (p["cap_r"], top - p["cap_t"], top, p["fillet"]),
    ], res)
    if not res.rounded:
        return solid
    holes = []
    for k in range(4):
        a = math.pi / 4.0 + k * math.pi / 2.0
        c = (p["bolt_circle_r"] * math.cos(a), p["bolt_circle_r"] * math.sin(a), 0.0)
        holes.append(rounded_cylinder(p["bolt_r"], (-0.01, p["flange_t"] + 0.01), "z", c, 0.0, res))
    return difference(solid, holes)


def link1(p: dict, joint2_z: float, res: Resolution) -> trimesh.Trimesh:
    disc = rounded_cylinder(p["disc_r"], (0.002, 0.002 + p["disc_t"]), "z", (0, 0, 0), p["fillet"], res)
    shoulder = _cyl(p, "shoulder_r", p["shoulder_y"], "y", (0, 0, joint2_z), res)
    column_foot = rounded_cylinder(p["shoulder_r"] * 0.9, (0.01, 0.03), "z", (0, 0, 0), 0.0, res)
    column = hull([column_foot, shoulder])
    # The motor reaches into the shoulder housing so no faces coincide.
    motor_span = (p["motor_y"][0], p["motor_y"][1] + 0.005)
    motor = _cyl(p, "motor_r", motor_span, "y", (0, 0, joint2_z), res)
    return union([disc, column, motor])


def link2(p: dict, joint3_z: float, res: Resolution) -> trimesh.Trimesh:
    shoulder = _cyl(p, "shoulder_r", p["y"], "y", (0, 0, 0), res)
    elbow = _cyl(p, "elbow_r", p["y"], "y", (0, 0, joint3_z), res)
    plate = hull([shoulder, elbow])
    cap_span = (p["y"][1] - 0.002, p["y"][1] + p["cap_t"])
    caps = [_cyl(p, "cap_r", cap_span, "y", (0, 0, z), res) for z in (0.0, joint3_z)]
    return union([plate, *caps])


def link3(p: dict, joint4_x: float, res: Resolution) -> trimesh.Trimesh:
    elbow = _cyl(p, "elbow_r", p["y"], "y", (0, 0, 0), res)
    tube = _cyl(p, "tube_r", p["tube_x"], "x", (0, 0, 0), res)
    body = hull([elbow, tube])
    cap_span = (p["y"][0] - 0.018, p["y"][0] + 0.002)
    cap = rounded_cylinder(p["elbow_r"] * 0.75, cap_span, "y", (0, 0, 0), p["fillet"], res)
    return union([body, cap])


def link4(p: dict, joint5_x: float, res: Resolution) -> trimesh.Trimesh:
    tube = _cyl(p, "tube_r", (p["tube_x"][0], p["tube_x"][1] - 0.01), "x", (0, 0, 0), res)
    # A slightly thicker neck swallows the tube's end: no coincident surfaces.
    neck = rounded_cylinder(p["tube_r"] * 1.08, (p["tube_x"][1] - 0.02, p["tube_x"][1]), "x", (0, 0, 0), 0.0, res)
    wrist = _cyl(p, "wrist_r", (-p["fork_y"], p["fork_y"]), "y", (joint5_x, 0, 0), res)
    fork = hull([neck, wrist])
    if not res.rounded:
        return union([tube, fork])
    slot = trimesh.creation.box(
        bounds=[[p["slot_x"], -p["slot_half_w"], -0.2], [joint5_x + 0.2, p["slot_half_w"], 0.2]]
    )
    return union([tube, difference(fork, [slot])])


def link5(p: dict, joint6_x: float, res: Resolution) -> trimesh.Trimesh:
    hub = _cyl(p, "hub_r", (-p["hub_half_w"], p["hub_half_w"]), "y", (0, 0, 0), res)
    root = _cyl(p, "tube_r", (-p["tube_r"], p["tube_r"]), "y", (0, 0, 0), res)
    tube = _cyl(p, "tube_r", p["tube_x"], "x", (0, 0, 0), res)
    return union([hub, hull([root, tube])])


def link6(p: dict, res: Resolution) -> trimesh.Trimesh:
    return rounded_cylinder(p["flange_r"], (0.0005, p["flange_t"]), "z", (0, 0, 0), p["fillet"], res)


def palm(p: dict, res: Resolution) -> trimesh.Trimesh:
    hub = rounded_cylinder(p["hub_r"], (0.0, 0.014), "z", (0, 0, 0), 0.0, res)
    dx, dy = p["depth_x"] / 2.0, p["width_y"] / 2.0
    housing = rounded_box((-dx, -dy, 0.01), (dx, dy, p["height_z"]), p["fillet"], res)
    return union([hub, housing])


def finger(f: dict, pad: dict, res: Resolution) -> trimesh.Trimesh:
    """finger1's solid: pad face at y = 0, body towards +y, from the palm's lower face (z = 0) down."""
    wx, ty, lz = f["width_x"] / 2.0, f["thickness_y"], f["length_z"]
    y0 = pad["thickness_y"]
    # Plate and carriage are offset by a millimetre so none of their faces coincide.
    plate = rounded_box((-wx, y0, 0.001), (wx, y0 + ty, lz), f["fillet"], res)
    cx = f["carriage_x"] / 2.0
    carriage = rounded_box((-cx, y0 + 0.001, 0.0), (cx, y0 + f["carriage_y"], f["carriage_z"]), f["fillet"], res)
    px = pad["width_x"] / 2.0
    pad_lo, pad_hi = pad_span(f, pad)
    pad_solid = rounded_box((-px, 0.0, pad_lo), (px, y0 + 0.001, pad_hi), f["fillet"], res)
    return union([plate, carriage, pad_solid])


def cup(p: dict, res: Resolution) -> trimesh.Trimesh:
    """The suction cup: a short cylinder on link6's flange, from the flange (z = 0) to its face (z = length)."""
    return rounded_cylinder(p["radius"], (0.0, p["length"]), "z", (0, 0, 0), p["fillet"], res)


def pad_span(f: dict, pad: dict) -> tuple[float, float]:
    hi = f["length_z"] - pad["tip_gap_z"]
    return hi - pad["length_z"], hi


def mirror_finger(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """finger2 = finger1 turned half a turn about z (its joint moves along -y)."""
    out = mesh.copy()
    out.apply_transform(trimesh.transformations.rotation_matrix(math.pi, [0.0, 0.0, 1.0]))
    return out


def collision_hull(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    return quantize(hull([mesh]))
