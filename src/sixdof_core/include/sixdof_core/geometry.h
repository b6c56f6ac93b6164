#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace sixdof_core {

// The kinds of Shape (the primitives of shape_msgs/SolidPrimitive, plus meshes).
enum class ShapeType { kBox, kSphere, kCylinder, kMesh };

// A collision or visual shape as the URDF/SRDF, a planning-scene object or a simulator world file describes
// it: the one shape value type of the core and the simulator. Cylinders are along their local z axis.
struct Shape {
  using Type = ShapeType;
  Type type = Type::kBox;
  Eigen::Vector3d box_size = Eigen::Vector3d::Zero();  // full extents (kBox)
  double radius = 0.0;                                  // kSphere, kCylinder
  double length = 0.0;                                  // kCylinder, along its z axis
  // kMesh: the URI or path as written (package://pkg/path, file:///path, a path), and the existing absolute
  // file it resolves to. The robot model sets both; a shape from elsewhere may carry only mesh_resource until
  // its user resolves it (the simulator, against its package search roots).
  std::string mesh_resource;
  std::string mesh_path;
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
