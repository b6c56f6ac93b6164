"""STL mesh loading (binary and ASCII) into shape_msgs/Mesh, for PlanningScene.add_mesh."""

from __future__ import annotations

import struct
from collections.abc import Sequence

from geometry_msgs.msg import Point
from shape_msgs.msg import Mesh, MeshTriangle

from .exceptions import SixdofCommanderError


def _ascii_triangles(text: str, path: str) -> list[tuple[tuple[float, float, float], ...]]:
    vertices = []
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "vertex":
            if len(words) != 4:
                raise SixdofCommanderError(f"malformed vertex line in STL file '{path}': '{line.strip()}'")
            vertices.append(tuple(float(w) for w in words[1:]))
    if not vertices or len(vertices) % 3:
        raise SixdofCommanderError(f"STL file '{path}' has {len(vertices)} vertices, not a positive multiple of 3")
    return [tuple(vertices[i : i + 3]) for i in range(0, len(vertices), 3)]


def _binary_triangles(data: bytes, path: str) -> list[tuple[tuple[float, float, float], ...]]:
    if len(data) < 84:
        raise SixdofCommanderError(f"STL file '{path}' is too short ({len(data)} bytes)")
    (count,) = struct.unpack_from("<I", data, 80)
    if len(data) < 84 + 50 * count:
        raise SixdofCommanderError(f"STL file '{path}' announces {count} triangles but is {len(data)} bytes long")
    triangles = []
    for i in range(count):
        values = struct.unpack_from("<12f", data, 84 + 50 * i)
        triangles.append((values[3:6], values[6:9], values[9:12]))
    return triangles


def load_stl(path: str, scale: Sequence[float] = (1.0, 1.0, 1.0)) -> Mesh:
    """The mesh of an STL file, each axis scaled, with shared vertices merged."""
    if not path.lower().endswith(".stl"):
        raise SixdofCommanderError(f"mesh file '{path}' is not an STL file (only .stl meshes are supported)")
    try:
        with open(path, "rb") as stream:
            data = stream.read()
    except OSError as err:
        raise SixdofCommanderError(f"cannot read mesh file '{path}': {err}") from err
    # Binary STLs may also start with 'solid'; the size check tells them apart.
    is_binary = len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]
    if is_binary:
        triangles = _binary_triangles(data, path)
    else:
        triangles = _ascii_triangles(data.decode("ascii", errors="replace"), path)
    mesh = Mesh()
    index: dict[tuple[float, float, float], int] = {}
    for triangle in triangles:
        ids = []
        for vertex in triangle:
            key = (vertex[0] * scale[0], vertex[1] * scale[1], vertex[2] * scale[2])
            if key not in index:
                index[key] = len(mesh.vertices)
                mesh.vertices.append(Point(*key))
            ids.append(index[key])
        mesh.triangles.append(MeshTriangle(vertex_indices=ids))
    return mesh
