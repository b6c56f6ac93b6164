"""The robot's own points: per link the bounding box (in the link frame) of its URDF collision and visual
geometry, and per end effector one box around the whole hand (its links and the space between the fingers,
where a held object is), both padded. Posed from tf each frame, they mask the cloud (as MoveIt's self filter
does with the links' shapes)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from xml.etree import ElementTree

import numpy as np

from .detection import Box
from .world import rotation_rpy

LinkBoxes = dict[str, tuple[np.ndarray, np.ndarray]]  # link -> (centre, half extents) in the link frame
VertexLoader = Callable[[str, list[float]], np.ndarray]  # (mesh URI, scale) -> Nx3 vertices


def _floats(text: str | None, count: int, default: Sequence[float]) -> list[float]:
    if text is None:
        return list(default)
    values = [float(v) for v in text.split()]
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise ValueError(f"URDF: expected {count} numbers, got '{text}'")
    return values


def _geometry_points(
    geometry: ElementTree.Element, load_vertices: Callable[[str, list[float]], np.ndarray]
) -> np.ndarray:
    """Points whose bounding box is the geometry's (its own frame)."""
    shape = next(iter(geometry), None)
    if shape is None:
        raise ValueError("URDF: <geometry> without a shape")
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    if shape.tag == "box":
        return corners * np.array(_floats(shape.get("size"), 3, ())) / 2.0
    if shape.tag == "cylinder":
        r, length = float(shape.get("radius")), float(shape.get("length"))
        return corners * np.array([r, r, length / 2.0])
    if shape.tag == "sphere":
        return corners * float(shape.get("radius"))
    if shape.tag == "mesh":
        return load_vertices(shape.get("filename", ""), _floats(shape.get("scale"), 3, (1.0, 1.0, 1.0)))
    raise ValueError(f"URDF: unsupported geometry <{shape.tag}>")


def link_boxes(urdf_text: str, load_vertices: VertexLoader) -> LinkBoxes:
    """Per link with geometry, the bounding box of its collision and visual shapes in the link frame."""
    boxes: LinkBoxes = {}
    for link in ElementTree.fromstring(urdf_text).iter("link"):
        points = []
        for element in list(link.iter("collision")) + list(link.iter("visual")):
            geometry = element.find("geometry")
            if geometry is None:
                continue
            origin = element.find("origin")
            xyz = _floats(origin.get("xyz") if origin is not None else None, 3, (0.0, 0.0, 0.0))
            rpy = _floats(origin.get("rpy") if origin is not None else None, 3, (0.0, 0.0, 0.0))
            local = _geometry_points(geometry, load_vertices)
            points.append(local @ rotation_rpy(*rpy).T + np.array(xyz))
        if points:
            allp = np.concatenate(points)
            low, high = allp.min(axis=0), allp.max(axis=0)
            boxes[link.get("name")] = ((low + high) / 2.0, (high - low) / 2.0)
    return boxes


def posed_boxes(boxes: LinkBoxes, poses: Mapping[str, np.ndarray]) -> list[Box]:
    """The link boxes at the links' 4x4 poses (links without a pose are skipped)."""
    out = []
    for link, (centre, half) in boxes.items():
        if link in poses:
            pose = poses[link]
            out.append(Box(pose[:3, :3] @ centre + pose[:3, 3], pose[:3, :3], half))
    return out


def hand_box(boxes: LinkBoxes, poses: Mapping[str, np.ndarray], parent: str, links: Iterable[str]) -> Box | None:
    """One box, aligned with the parent link, around the boxes of the hand's links (fingers included)."""
    if parent not in poses:
        return None
    to_parent = np.linalg.inv(poses[parent])
    corners = []
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    for link in links:
        if link in boxes and link in poses:
            centre, half = boxes[link]
            local = centre + signs * half
            relative = to_parent @ poses[link]
            corners.append(local @ relative[:3, :3].T + relative[:3, 3])
    if not corners:
        return None
    allc = np.concatenate(corners)
    low, high = allc.min(axis=0), allc.max(axis=0)
    pose = poses[parent]
    return Box(pose[:3, :3] @ ((low + high) / 2.0) + pose[:3, 3], pose[:3, :3], (high - low) / 2.0)
