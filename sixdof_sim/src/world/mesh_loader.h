#pragma once
// Private: mesh files -> vertex clouds for convex hulls (assimp), URI resolution.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace sixdof_sim {

// Resolves package://pkg/rel (against <root>/pkg/rel, or <root>/rel when root's last component is pkg),
// file:///abs and plain paths. Returns the existing file path, or an empty string.
std::string resolveResource(const std::string& uri, const std::vector<std::string>& search_roots);

// Caches the vertices of each mesh file (unscaled, in the file's frame).
class MeshCache {
 public:
  // All vertices of all meshes in the file. Throws std::invalid_argument naming the file when it
  // cannot be read or has no vertices.
  const std::vector<Eigen::Vector3d>& vertices(const std::string& path);

 private:
  std::map<std::string, std::vector<Eigen::Vector3d>> cache_;
};

}  // namespace sixdof_sim
