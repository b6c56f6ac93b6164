// PackageResolver: package:// and file:// URIs to paths (search roots, ROS_PACKAGE_PATH, explicit folders).
#include <tinyxml2.h>

#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

namespace fs = std::filesystem;

namespace {

std::string readPackageName(const fs::path& package_xml) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(package_xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return "";
  const auto* name = doc.RootElement()->FirstChildElement("name");
  return name && name->GetText() ? std::string(name->GetText()) : "";
}

// Finds the directory of `package` below root, at most `depth` levels deep, skipping hidden folders.
std::optional<fs::path> findPackage(const fs::path& root, const std::string& package, int depth) {
  std::error_code ec;
  if (fs::exists(root / "package.xml", ec)) {
    // A package does not contain other packages.
    if (readPackageName(root / "package.xml") == package) return root;
    return std::nullopt;
  }
  if (depth == 0) return std::nullopt;
  if (fs::exists(root / package / "package.xml", ec) && readPackageName(root / package / "package.xml") == package) {
    return root / package;
  }
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const auto& entry = *it;
    if (!entry.is_directory(ec) || entry.path().filename().string().front() == '.') continue;
    if (auto found = findPackage(entry.path(), package, depth - 1)) return found;
  }
  return std::nullopt;
}

}  // namespace

PackageResolver PackageResolver::fromSearchRoots(const std::vector<std::string>& roots) {
  PackageResolver resolver;
  resolver.roots_ = roots;
  return resolver;
}

PackageResolver PackageResolver::fromRosPackagePath(const std::string& ros_package_path) {
  std::vector<std::string> roots;
  std::stringstream in(ros_package_path);
  std::string root;
  while (std::getline(in, root, ':')) {
    if (!root.empty()) roots.push_back(root);
  }
  return fromSearchRoots(roots);
}

PackageResolver PackageResolver::fromMap(const std::map<std::string, std::string>& package_dirs) {
  PackageResolver resolver;
  resolver.package_dirs_ = package_dirs;
  return resolver;
}

PackageResolver& PackageResolver::addPackage(const std::string& package, const std::string& directory) {
  package_dirs_[package] = directory;
  return *this;
}

std::string PackageResolver::packageDirectory(const std::string& package) const {
  auto it = package_dirs_.find(package);
  if (it != package_dirs_.end()) return it->second;
  for (const auto& root : roots_) {
    if (auto found = findPackage(root, package, 3)) return found->string();
  }
  std::string where;
  for (const auto& root : roots_) where += (where.empty() ? "" : ":") + root;
  for (const auto& [name, dir] : package_dirs_) where += (where.empty() ? "" : ", ") + name + "=" + dir;
  throw RobotModelError("package '" + package + "' not found (searched: " + (where.empty() ? "nothing" : where) +
                        ")");
}

std::string PackageResolver::resolve(const std::string& uri) const {
  fs::path path;
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (uri.rfind(package_scheme, 0) == 0) {
    const std::string rest = uri.substr(package_scheme.size());
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) throw RobotModelError("malformed package URI '" + uri + "'");
    std::string directory;
    try {
      directory = packageDirectory(rest.substr(0, slash));
    } catch (const RobotModelError& e) {
      throw RobotModelError("'" + uri + "': " + e.what());
    }
    path = fs::path(directory) / rest.substr(slash + 1);
  } else if (uri.rfind(file_scheme, 0) == 0) {
    path = uri.substr(file_scheme.size());
  } else {
    path = uri;
  }
  if (!path.is_absolute()) throw RobotModelError("mesh '" + uri + "' is neither a package URI nor an absolute path");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw RobotModelError("mesh '" + uri + "' resolves to '" + path.string() + "', which does not exist");
  }
  return path.lexically_normal().string();
}

}  // namespace sixdof_core
