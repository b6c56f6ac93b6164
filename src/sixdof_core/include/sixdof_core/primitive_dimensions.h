#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "sixdof_core/geometry.h"

namespace sixdof_core {

// Boxes, spheres and cylinders as shape_msgs/SolidPrimitive lists their dimensions: BOX [x, y, z], SPHERE [radius],
// CYLINDER [height, radius]. The nodes map the message's type constants to ShapeType; the order lives here only.

// How many dimensions a primitive of `type` has in that order (0 for a mesh).
inline std::size_t primitiveDimensionCount(ShapeType type) {
  switch (type) {
    case ShapeType::kBox:
      return 3;
    case ShapeType::kSphere:
      return 1;
    case ShapeType::kCylinder:
      return 2;
    case ShapeType::kMesh:
      break;
  }
  return 0;
}

// A box's, sphere's or cylinder's dimensions in that order (none for a mesh).
inline std::vector<double> primitiveDimensions(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kBox:
      return {shape.box_size.x(), shape.box_size.y(), shape.box_size.z()};
    case ShapeType::kSphere:
      return {shape.radius};
    case ShapeType::kCylinder:
      return {shape.length, shape.radius};
    case ShapeType::kMesh:
      break;
  }
  return {};
}

// The box, sphere or cylinder with `dimensions` in that order; none when their number is not
// primitiveDimensionCount(type) (or `type` is a mesh). Their values are the caller's to check.
inline std::optional<Shape> primitiveShape(ShapeType type, const std::vector<double>& dimensions) {
  const std::size_t count = primitiveDimensionCount(type);
  if (count == 0 || dimensions.size() != count) return std::nullopt;
  Shape shape;
  shape.type = type;
  if (type == ShapeType::kBox) {
    shape.box_size = Eigen::Vector3d(dimensions[0], dimensions[1], dimensions[2]);
  } else if (type == ShapeType::kSphere) {
    shape.radius = dimensions[0];
  } else {
    shape.length = dimensions[0];
    shape.radius = dimensions[1];
  }
  return shape;
}

}  // namespace sixdof_core
