#include "camera_meshes.h"

#include <array>
#include <cmath>

#include "sixdof_core/mesh_loader.h"
#include "sixdof_sim/world.h"

namespace sixdof_sim {
namespace {

// Cylinders are prisms of this many sides: the flats lie at most r (1 - cos(pi / n)) = 0.05 % of the
// radius inside the true surface (0.01 mm at r = 2.5 cm).
constexpr int kCylinderSides = 96;

}  // namespace

TriangleMesh unitBox() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.insert(m.vertices.end(), {(i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f});
  }
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return m;
}

TriangleMesh unitCylinder() {
  TriangleMesh m;
  const unsigned n = kCylinderSides;
  for (unsigned i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const float x = static_cast<float>(std::cos(a)), y = static_cast<float>(std::sin(a));
    m.vertices.insert(m.vertices.end(), {x, y, -0.5f, x, y, 0.5f});
  }
  m.vertices.insert(m.vertices.end(), {0.0f, 0.0f, -0.5f, 0.0f, 0.0f, 0.5f});
  const unsigned bottom = 2 * n, top = 2 * n + 1;
  for (unsigned i = 0; i < n; ++i) {
    const unsigned j = (i + 1) % n;
    m.indices.insert(m.indices.end(), {2 * i, 2 * j, 2 * i + 1, 2 * i + 1, 2 * j, 2 * j + 1});
    m.indices.insert(m.indices.end(), {bottom, 2 * j, 2 * i, top, 2 * i + 1, 2 * j + 1});
  }
  return m;
}

TriangleMesh unitSquare() {
  TriangleMesh m;
  m.vertices = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TriangleMesh meshFileTriangles(const std::string& path) {
  // Unit scale: one cached copy per file serves every scale (the instance transform scales it).
  const sixdof_core::MeshLoadResult loaded = sixdof_core::loadMesh(path);
  if (!loaded.ok()) throw WorldError(loaded.message);
  TriangleMesh out;
  out.vertices.reserve(3 * loaded.mesh->vertices.size());
  for (const Eigen::Vector3d& p : loaded.mesh->vertices) {
    out.vertices.insert(out.vertices.end(),
                        {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  out.indices.reserve(3 * loaded.mesh->triangles.size());
  for (const std::array<int, 3>& t : loaded.mesh->triangles) {
    out.indices.insert(out.indices.end(),
                       {static_cast<unsigned>(t[0]), static_cast<unsigned>(t[1]), static_cast<unsigned>(t[2])});
  }
  return out;
}

}  // namespace sixdof_sim
