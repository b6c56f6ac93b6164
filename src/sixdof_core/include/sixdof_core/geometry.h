#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace sixdof_core {

// A collision or visual shape as the URDF/SRDF or a planning-scene object describes it.
struct Shape {
  enum class Type { kBox, kSphere, kCylinder, kMesh };
  Type type = Type::kBox;
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();  // full extents (kBox)
  double radius = 0.0;                                  // kSphere, kCylinder
  double length = 0.0;                                  // kCylinder, along its z axis
  std::string mesh_path;                                // kMesh: resolved absolute file path
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
};

// A shape placed in a frame (a link's frame, or an object's frame).
struct PlacedShape {
  Shape shape;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

// The collision geometry of one robot link, in the link's frame.
struct LinkGeometry {
  std::string link_name;
  std::vector<PlacedShape> shapes;
};

}  // namespace sixdof_core
