#include "sixdof_core/mesh_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <tuple>

namespace sixdof_core {
namespace {

void collectNode(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, const Eigen::Vector3d& scale,
                 MeshData* out) {
  const aiMatrix4x4 transform = parent * node->mTransformation;
  for (unsigned int m = 0; m < node->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    const int offset = static_cast<int>(out->vertices.size());
    for (unsigned int v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = transform * mesh->mVertices[v];
      out->vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
    }
    for (unsigned int f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      // Points and lines (possible in DAE files) carry no volume for collision.
      if (face.mNumIndices != 3) continue;
      out->triangles.push_back({offset + static_cast<int>(face.mIndices[0]),
                                offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned int c = 0; c < node->mNumChildren; ++c) collectNode(scene, node->mChildren[c], transform, scale, out);
}

// Vertices at the same position become one, and the triangles index it: STL files (and assimp, keeping a vertex per
// face normal) give every triangle corners of its own. A convex mesh is then a closed hull whose edges FCL walks to
// find support points, instead of scanning three copies of every corner.
void weldVertices(MeshData* mesh) {
  auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
  };
  std::map<Eigen::Vector3d, int, decltype(less)> index(less);
  std::vector<Eigen::Vector3d> welded;
  std::vector<int> remap(mesh->vertices.size());
  for (std::size_t v = 0; v < mesh->vertices.size(); ++v) {
    const auto [it, added] = index.emplace(mesh->vertices[v], static_cast<int>(welded.size()));
    if (added) welded.push_back(mesh->vertices[v]);
    remap[v] = it->second;
  }
  for (auto& t : mesh->triangles) {
    for (int& k : t) k = remap[k];
  }
  mesh->vertices = std::move(welded);
}

struct CacheKey {
  std::string path;
  double sx, sy, sz;
  bool operator<(const CacheKey& o) const { return std::tie(path, sx, sy, sz) < std::tie(o.path, o.sx, o.sy, o.sz); }
};

}  // namespace

bool isConvexMesh(const MeshData& mesh) {
  if (mesh.triangles.size() < 4) return false;
  Eigen::Vector3d lo = mesh.vertices.front(), hi = mesh.vertices.front();
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double tol = 1e-6 * (hi - lo).norm();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    Eigen::Vector3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    const double len = n.norm();
    if (len < 1e-15) continue;  // degenerate sliver: no plane to test
    n /= len;
    bool above = false, below = false;
    for (const auto& v : mesh.vertices) {
      const double d = n.dot(v - a);
      above |= d > tol;
      below |= d < -tol;
      if (above && below) return false;
    }
  }
  return true;
}

MeshLoadResult loadMesh(const std::string& path, const Eigen::Vector3d& scale) {
  MeshLoadResult result;
  if (!scale.allFinite() || (scale.array() <= 0.0).any()) {
    std::ostringstream msg;
    msg << "mesh '" << path << "': scale must be positive and finite, got (" << scale.transpose() << ")";
    result.fail(MeshLoadStatus::kInvalidScale, msg.str());
    return result;
  }
  static std::mutex mutex;
  static std::map<CacheKey, std::shared_ptr<const MeshData>> cache;
  const CacheKey key{path, scale.x(), scale.y(), scale.z()};
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) {
      result.mesh = it->second;
      return result;
    }
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    result.fail(MeshLoadStatus::kUnreadable, "mesh '" + path + "': cannot be read: " + importer.GetErrorString());
    return result;
  }
  auto mesh = std::make_shared<MeshData>();
  // Collada files may declare a non-metre unit or a Y-up axis in their root node transform: kept, as rviz does.
  collectNode(scene, scene->mRootNode, aiMatrix4x4(), scale, mesh.get());
  if (mesh->triangles.empty()) {
    result.fail(MeshLoadStatus::kNoTriangles, "mesh '" + path + "': contains no triangles");
    return result;
  }
  weldVertices(mesh.get());
  mesh->convex = isConvexMesh(*mesh);
  {
    std::lock_guard<std::mutex> lock(mutex);
    cache.emplace(key, mesh);
  }
  result.mesh = mesh;
  return result;
}

}  // namespace sixdof_core
