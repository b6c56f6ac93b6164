"""How far a gripper reaches beyond its tool centre point along the tool axis, from the URDF's collision
geometry: a top-down grasp must keep the fingertips above the surface the object stands on."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from xml.etree import ElementTree

import numpy as np

from .exceptions import SixdofCommanderError
from .mesh import load_stl
from .robot_model import RobotDescription
from .transforms import homogeneous, matrix_from_rpy


def _floats(text: str | None, default: str, what: str) -> list[float]:
    try:
        values = [float(v) for v in (text if text is not None else default).split()]
    except ValueError as err:
        raise SixdofCommanderError(f"{what}: '{text}' is not a list of numbers") from err
    if not all(math.isfinite(v) for v in values):
        raise SixdofCommanderError(f"{what}: '{text}' is not finite")
    return values


def _corners(half: Iterable[float]) -> np.ndarray:
    hx, hy, hz = half
    return np.array([[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])


def collision_points(urdf: ElementTree.Element, link: str, resolve: Callable[[str], str]) -> np.ndarray:
    """Points (N x 3, link frame) whose convex hull bounds the link's collision geometry in the parsed URDF: the
    corners of boxes and of the boxes around cylinders and spheres, and the vertices of STL meshes."""
    element = next((e for e in urdf.findall("link") if e.get("name") == link), None)
    if element is None:
        raise SixdofCommanderError(f"link '{link}' is not in the URDF")
    points = []
    for collision in element.findall("collision"):
        what = f"URDF link '{link}' <collision>"
        origin = collision.find("origin")
        xyz = _floats(origin.get("xyz") if origin is not None else None, "0 0 0", f"{what} origin xyz")
        rpy = _floats(origin.get("rpy") if origin is not None else None, "0 0 0", f"{what} origin rpy")
        frame = homogeneous(xyz, matrix_from_rpy(*rpy))
        geometry = collision.find("geometry")
        shape = geometry[0] if geometry is not None and len(geometry) else None
        if shape is None:
            continue
        if shape.tag == "box":
            local = _corners(v / 2.0 for v in _floats(shape.get("size"), "", f"{what} box size"))
        elif shape.tag == "cylinder":
            radius = _floats(shape.get("radius"), "", f"{what} cylinder radius")[0]
            length = _floats(shape.get("length"), "", f"{what} cylinder length")[0]
            local = _corners((radius, radius, length / 2.0))
        elif shape.tag == "sphere":
            radius = _floats(shape.get("radius"), "", f"{what} sphere radius")[0]
            local = _corners((radius, radius, radius))
        elif shape.tag == "mesh":
            scale = _floats(shape.get("scale"), "1 1 1", f"{what} mesh scale")
            mesh = load_stl(resolve(shape.get("filename", "")), scale)
            local = np.array([[p.x, p.y, p.z] for p in mesh.vertices])
        else:
            raise SixdofCommanderError(f"{what}: unknown geometry <{shape.tag}>")
        if len(local):
            points.append(local @ frame[:3, :3].T + frame[:3, 3])
    return np.vstack(points) if points else np.zeros((0, 3))


def gripper_reach(
    urdf_xml: str,
    description: RobotDescription,
    tip_link: str,
    tcp_in_tip: np.ndarray,
    resolve: Callable[[str], str],
) -> float:
    """How far the links below tip_link (fingers at zero) reach beyond the tcp along the tool z axis (m, >= 0)."""
    tip_in_tcp = np.linalg.inv(tcp_in_tip)
    urdf = ElementTree.fromstring(urdf_xml)
    reach = 0.0
    for link in description.descendant_links(tip_link):
        points = collision_points(urdf, link, resolve)
        if not len(points):
            continue
        link_in_tcp = tip_in_tcp @ description.chain_transform(tip_link, link)
        z = points @ link_in_tcp[2, :3] + link_in_tcp[2, 3]
        reach = max(reach, float(z.max()))
    return reach
