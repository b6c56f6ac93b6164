"""STL loading for PlanningScene.add_mesh: binary and ASCII, merged vertices, scaling, errors."""

import struct

import pytest
from sixdof_commander import SixdofCommanderError
from sixdof_commander.mesh import load_stl

# A tetrahedron: 4 vertices, 4 triangles.
V = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def write_binary(path, faces=FACES, count=None):
    data = b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(faces) if count is None else count)
    for face in faces:
        data += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *V[i]) for i in face) + b"\0\0"
    path.write_bytes(data)


def write_ascii(path):
    lines = ["solid tetra"]
    for face in FACES:
        lines += ["facet normal 0 0 0", "outer loop", *(f"vertex {V[i][0]} {V[i][1]} {V[i][2]}" for i in face)]
        lines += ["endloop", "endfacet"]
    path.write_text("\n".join(lines + ["endsolid tetra"]))


@pytest.mark.parametrize("writer", [write_binary, write_ascii])
def test_tetrahedron_vertices_are_merged(tmp_path, writer):
    path = tmp_path / "tetra.stl"
    writer(path)
    mesh = load_stl(str(path), (2.0, 1.0, 0.5))
    assert len(mesh.vertices) == 4
    assert len(mesh.triangles) == 4
    assert sorted((p.x, p.y, p.z) for p in mesh.vertices) == sorted((2 * x, y, 0.5 * z) for x, y, z in V)
    first = mesh.triangles[0].vertex_indices
    assert [(mesh.vertices[i].x, mesh.vertices[i].y) for i in first] == [(0.0, 0.0), (0.0, 1.0), (2.0, 0.0)]


def test_wrong_extension_truncated_and_missing_files_are_rejected(tmp_path):
    with pytest.raises(SixdofCommanderError, match="not an STL file"):
        load_stl(str(tmp_path / "mesh.dae"))
    with pytest.raises(SixdofCommanderError, match="cannot read mesh file"):
        load_stl(str(tmp_path / "missing.stl"))
    bad = tmp_path / "bad.stl"
    bad.write_text("solid x\nvertex 0 0 0\nvertex 1 0 0\nendsolid x\n")
    with pytest.raises(SixdofCommanderError, match="2 vertices, not a positive multiple of 3"):
        load_stl(str(bad))
