"""The robot's own points: per link the bounding box (in the link frame) of its collision shapes in move_group's
robot model (get_robot_model with collision geometry), and per end effector one box around the whole hand (its
links and the space between the fingers, where a held object is), both padded. Posed from tf each frame, they
mask the cloud (as MoveIt's self filter does with the links' collision shapes)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
from sixdof_commander.robot_model import geometry_points

from .detection import Box

LinkBoxes = dict[str, tuple[np.ndarray, np.ndarray]]  # link -> (centre, half extents) in the link frame


def link_boxes(geometries: Iterable[Any]) -> LinkBoxes:
    """Per link with collision shapes (sixdof_msgs/RobotModelLinkGeometry, as RobotDescription.collision holds
    them), the bounding box of its shapes in the link frame."""
    boxes: LinkBoxes = {}
    for geometry in geometries:
        points = geometry_points(geometry)
        if len(points):
            low, high = points.min(axis=0), points.max(axis=0)
            boxes[geometry.link_name] = ((low + high) / 2.0, (high - low) / 2.0)
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
