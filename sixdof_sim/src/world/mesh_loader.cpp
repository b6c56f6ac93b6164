#include "mesh_loader.h"

#include <filesystem>

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

}  // namespace sixdof_sim
