#pragma once
// Private: the checked YAML readers of the world file parser (world_file.cpp: objects, tables, bins, cameras;
// world_file_conveyors.cpp: conveyors, sources, sinks). Every failure throws WorldFileError naming the file, the
// line, the entry and the problem.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sixdof_sim/world_file.h"

namespace sixdof_sim {

class WorldFileReader {
 public:
  WorldFileReader(std::string source, std::string base_dir)
      : source_(std::move(source)), base_dir_(std::move(base_dir)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& context, const std::string& problem) const {
    std::ostringstream out;
    out << source_;
    if (node.IsDefined() && node.Mark().line >= 0) out << ":" << node.Mark().line + 1;
    out << ": " << (context.empty() ? "" : context + ": ") << problem;
    throw WorldFileError(out.str());
  }

  void checkKeys(const YAML::Node& map, const std::string& context, const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, context, "must be a mapping");
    for (const auto& entry : map) {
      const std::string key = entry.first.as<std::string>();
      if (!allowed.count(key)) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(entry.first, context, "unknown key '" + key + "' (allowed: " + list + ")");
      }
    }
  }

  // A scalar of type T (`expected` says what it must be in the message).
  template <typename T>
  T scalar(const YAML::Node& node, const std::string& context, const std::string& key, const char* expected) const {
    if (!node.IsScalar()) fail(node, context, "'" + key + "' must be " + expected);
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail(node, context, "'" + key + "' must be " + expected + ", got '" + node.Scalar() + "'");
    }
  }

  double number(const YAML::Node& node, const std::string& context, const std::string& key) const {
    return scalar<double>(node, context, key, "a number");
  }

  bool boolean(const YAML::Node& node, const std::string& context, const std::string& key) const {
    return scalar<bool>(node, context, key, "true or false");
  }

  std::string text(const YAML::Node& node, const std::string& context, const std::string& key) const {
    if (!node.IsScalar() || node.Scalar().empty()) fail(node, context, "'" + key + "' must be a non-empty string");
    return node.Scalar();
  }

  long long integer(const YAML::Node& node, const std::string& context, const std::string& key) const {
    return scalar<long long>(node, context, key, "an integer");
  }

  std::vector<double> numbers(const YAML::Node& node, const std::string& context, const std::string& key,
                              size_t size) const {
    if (!node.IsSequence() || node.size() != size) {
      fail(node, context, "'" + key + "' must be a list of " + std::to_string(size) + " numbers");
    }
    std::vector<double> out;
    for (const auto& item : node) out.push_back(number(item, context, key));
    return out;
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& context, const std::string& key) const {
    const std::vector<double> v = numbers(node, context, key, 3);
    return Eigen::Vector3d(v[0], v[1], v[2]);
  }

  Eigen::Isometry3d pose(const YAML::Node& map, const std::string& context) const {
    if (!map["position"]) fail(map, context, "'position' [x, y, z] is required");
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = vector3(map["position"], context, "position");
    if (map["rpy"]) {
      // Fixed-axis roll, pitch, yaw (URDF / tf2 setRPY): R = Rz(yaw) Ry(pitch) Rx(roll).
      const Eigen::Vector3d rpy = vector3(map["rpy"], context, "rpy");
      pose.linear() =
          (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
              .toRotationMatrix();
    }
    return pose;
  }

  Color color(const YAML::Node& node, const std::string& context) const {
    if (!node.IsSequence() || (node.size() != 3 && node.size() != 4)) {
      fail(node, context, "'color' must be [r, g, b] or [r, g, b, a] with components in [0, 1]");
    }
    const std::vector<double> c = numbers(node, context, "color", node.size());
    return Color{c[0], c[1], c[2], c.size() == 4 ? c[3] : 1.0};
  }

  std::string meshPath(const std::string& value) const {
    if (value.rfind("package://", 0) == 0 || value.rfind("file://", 0) == 0) return value;
    const std::filesystem::path path(value);
    if (path.is_absolute() || base_dir_.empty()) return value;
    return (std::filesystem::path(base_dir_) / path).lexically_normal().string();
  }

  // Calls item(element, "key[i]") for each element of the list root[key] (none when the key is absent).
  template <class Item>
  void forEachItem(const YAML::Node& root, const char* key, const Item& item) const {
    const YAML::Node items = root[key];
    if (!items) return;
    if (!items.IsSequence()) fail(items, key, "must be a list");
    for (size_t i = 0; i < items.size(); ++i) item(items[i], std::string(key) + "[" + std::to_string(i) + "]");
  }

 private:
  std::string source_;
  std::string base_dir_;
};

// The world file's conveyors, sources and sinks into spec (after its objects: belt names join `names`, the names
// of tables, objects and bin walls).
void readConveyors(const WorldFileReader& reader, const YAML::Node& root, std::set<std::string>* names,
                   WorldSpec* spec);

}  // namespace sixdof_sim
