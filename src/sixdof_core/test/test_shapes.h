#pragma once
// Test helper: shapes and poses in one line (the collision and occupancy map tests build many probes).
#include <string>

#include <Eigen/Geometry>

#include "sixdof_core/geometry.h"

namespace sixdof_test {

inline sixdof_core::Shape box(double x, double y, double z) {
  sixdof_core::Shape s;
  s.type = sixdof_core::Shape::Type::kBox;
  s.box_size << x, y, z;
  return s;
}

inline sixdof_core::Shape sphere(double r) {
  sixdof_core::Shape s;
  s.type = sixdof_core::Shape::Type::kSphere;
  s.radius = r;
  return s;
}

inline sixdof_core::Shape cylinder(double r, double length) {
  sixdof_core::Shape s;
  s.type = sixdof_core::Shape::Type::kCylinder;
  s.radius = r;
  s.length = length;
  return s;
}

inline sixdof_core::Shape mesh(const std::string& path) {
  sixdof_core::Shape s;
  s.type = sixdof_core::Shape::Type::kMesh;
  s.mesh_path = path;
  return s;
}

inline Eigen::Isometry3d at(double x, double y, double z) {
  return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
}

}  // namespace sixdof_test
