#pragma once
// Private to the camera renderer: the triangle meshes it hands to Embree (unit primitives and mesh files).

#include <string>
#include <vector>

namespace sixdof_sim {

// Embree's vertex and index buffer layouts.
struct TriangleMesh {
  std::vector<float> vertices;  // x, y, z per vertex
  std::vector<unsigned> indices;
};

// The cube [-0.5, 0.5]^3.
TriangleMesh unitBox();
// Radius 1, length 1 along z, centred at the origin (URDF and SolidPrimitive cylinders).
TriangleMesh unitCylinder();
// The square [-1, 1]^2 in the z = 0 plane.
TriangleMesh unitSquare();
// Every triangle of the mesh file, unscaled (the renderer scales instances), read by sixdof_core::loadMesh.
// Throws WorldError naming the path when the file cannot be read or has no triangles.
TriangleMesh meshFileTriangles(const std::string& path);

}  // namespace sixdof_sim
