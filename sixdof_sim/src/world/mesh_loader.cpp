#include "mesh_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <filesystem>
#include <functional>
#include <stdexcept>

namespace sixdof_sim {

std::string resolveResource(const std::string& uri, const std::vector<std::string>& search_roots) {
  namespace fs = std::filesystem;
  const std::string package_prefix = "package://";
  const std::string file_prefix = "file://";
  if (uri.rfind(package_prefix, 0) == 0) {
    const std::string rest = uri.substr(package_prefix.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos) return "";
    const std::string package = rest.substr(0, slash);
    const std::string relative = rest.substr(slash + 1);
    for (const std::string& root : search_roots) {
      const fs::path in_root = fs::path(root) / package / relative;
      if (fs::is_regular_file(in_root)) return in_root.string();
      const fs::path root_path = fs::path(root).lexically_normal();
      const std::string last = root_path.has_filename() ? root_path.filename().string()
                                                        : root_path.parent_path().filename().string();
      if (last == package && fs::is_regular_file(fs::path(root) / relative)) {
        return (fs::path(root) / relative).string();
      }
    }
    return "";
  }
  const std::string path = uri.rfind(file_prefix, 0) == 0 ? uri.substr(file_prefix.size()) : uri;
  return fs::is_regular_file(path) ? path : "";
}

const std::vector<Eigen::Vector3d>& MeshCache::vertices(const std::string& path) {
  const auto it = cache_.find(path);
  if (it != cache_.end()) return it->second;
  Assimp::Importer importer;
  // No post-processing that reorders or drops vertices beyond joining duplicates: the hull only needs points.
  const aiScene* scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::invalid_argument("mesh '" + path + "' cannot be read: " + importer.GetErrorString());
  }
  std::vector<Eigen::Vector3d> points;
  // Walk the node tree so node transforms (common in DAE files) are applied.
  std::function<void(const aiNode*, const aiMatrix4x4&)> visit = [&](const aiNode* node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node->mTransformation;
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D p = transform * mesh->mVertices[v];
        points.emplace_back(p.x, p.y, p.z);
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], transform);
  };
  visit(scene->mRootNode, aiMatrix4x4());
  if (points.size() < 4) throw std::invalid_argument("mesh '" + path + "' has fewer than 4 vertices");
  return cache_.emplace(path, std::move(points)).first->second;
}

}  // namespace sixdof_sim
