#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sixdof_core/result.h"

namespace sixdof_core {

// A triangle mesh in its file's frame, scale applied, node transforms of the file flattened.
struct MeshData {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  // Every face's plane has all vertices on one side (within a tolerance relative to the mesh size),
  // so the vertex set's convex hull is the mesh itself and GJK on the vertices is exact.
  bool convex = false;
};

enum class MeshLoadStatus {
  kSuccess,
  kInvalidScale,  // a scale component not positive or not finite
  kUnreadable,    // assimp cannot read the file
  kNoTriangles,   // the file holds no triangles
};

struct MeshLoadResult : Result<MeshLoadStatus> {
  std::shared_ptr<const MeshData> mesh;  // set on success
};

// Loads any format assimp reads (STL, OBJ, DAE, ...). Results are cached by (path, scale), so each
// file is read once per process; the cache is thread-safe. A mesh without triangles, a non-positive
// or non-finite scale and a file assimp cannot read are errors naming the path.
MeshLoadResult loadMesh(const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

// The convexity test loadMesh applies (exposed for tests and tools).
bool isConvexMesh(const MeshData& mesh);

}  // namespace sixdof_core
