#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/math/bv/AABB.h>

#include "obb.h"
#include "spheres.h"
#include "sixdof_core/collision.h"
#include "sixdof_core/geometry.h"

namespace sixdof_core {
namespace detail {

using GeometryPtr = std::shared_ptr<fcl::CollisionGeometryd>;

// One shape of a body, built for FCL.
struct ShapeInstance {
  GeometryPtr geometry;
  Eigen::Isometry3d origin;  // in the body's frame
  Obb obb;                   // in the shape's frame (geometry coordinates)
  bool origin_is_identity = false;
  std::vector<Sphere> spheres;  // robot shapes: the pre-check's covering spheres, in the shape's frame
};

inline SceneStatus error(SceneStatusCode code, const std::string& message) {
  return SceneStatus::failure(code, message);
}

// Builds the FCL geometry of a shape scaled about its origin and then padded. Null with *status set on an
// invalid shape or an unreadable mesh. Meshes are cached: one geometry per (file, scales, padding).
GeometryPtr makeGeometry(const Shape& shape, double scale, double padding, SceneStatus* status);

// Bounding box of an FCL geometry built by makeGeometry() (primitives exactly, meshes from their vertices).
Obb geometryObb(const fcl::CollisionGeometryd& geometry);

// The world-frame AABB of a geometry placed by tf.
fcl::AABBd worldAabb(const fcl::CollisionGeometryd& geometry, const Eigen::Isometry3d& tf);

}  // namespace detail
}  // namespace sixdof_core
