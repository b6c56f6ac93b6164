#pragma once

// The sphere model of the collision pre-check (CollisionScene::precheckMotion): spheres whose union contains a
// robot shape's FCL geometry, fitted once when the shape is built; a bounding-sphere tree of them per robot body; and
// world shapes as the pre-check measures distances to them.

#include <fcl/geometry/collision_geometry.h>

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "obb.h"

namespace sixdof_core {
namespace detail {

struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// Spheres in the geometry's frame whose union contains the geometry as FCL collides it. A sphere is itself. A box,
// a cylinder (through the prism around it) or a convex mesh (the hull of its vertices, what FCL's GJK sees) is cut
// by a grid along its oriented box `obb`; each cell's part is the convex hull of points found exactly (the solid's
// vertices in the cell and where segments between them cross the cell's planes), and gets the sphere around them.
// A non-convex mesh, a surface for FCL, gets the spheres around its triangles clipped to each cell.
std::vector<Sphere> coveringSpheres(const fcl::CollisionGeometryd& geometry, const Obb& obb);
// The same, fitted once per mesh geometry (mesh geometries are shared, see makeGeometry).
std::vector<Sphere> coveringSpheres(const std::shared_ptr<fcl::CollisionGeometryd>& geometry, const Obb& obb);

// A node of a body's bounding-sphere tree, in the body's link frame. Node 0 is the root; a leaf (left < 0) is one
// covering sphere. reach is the largest distance from the link frame's origin of any point in the node's leaf
// spheres: what a LinkMotionBound needs to bound how far they move.
struct SphereNode {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double reach = 0.0;
  int left = -1;
  int right = -1;
};

// The tree over spheres (link frame): split at the median of the widest spread of centres, down to single spheres.
std::vector<SphereNode> buildSphereTree(std::vector<Sphere> spheres);

// A world shape as the pre-check measures it: a box, sphere or cylinder exactly, any other shape by its oriented box.
struct ClearanceShape {
  enum class Kind { kBox, kSphere, kCylinder };
  Kind kind = Kind::kBox;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();        // world
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the shape's axes in the world (orthonormal)
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  // box: half extents; sphere: radius in x; cylinder: radius in x,
                                                   // half length in z (its axis)
};

// The shape of a geometry placed by tf (obb: the geometry's own oriented box, used for meshes).
ClearanceShape clearanceShape(const fcl::CollisionGeometryd& geometry, const Obb& obb, const Eigen::Isometry3d& tf);
// A world-axis-aligned box.
ClearanceShape clearanceBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

// Distance from a world point to the shape (0 inside it).
inline double pointDistance(const ClearanceShape& shape, const Eigen::Vector3d& point) {
  const Eigen::Vector3d p = shape.rotation.transpose() * (point - shape.center);
  switch (shape.kind) {
    case ClearanceShape::Kind::kSphere:
      return std::max(0.0, p.norm() - shape.half.x());
    case ClearanceShape::Kind::kCylinder: {
      const double radial = std::max(0.0, std::sqrt(p.x() * p.x() + p.y() * p.y()) - shape.half.x());
      const double axial = std::max(0.0, std::abs(p.z()) - shape.half.z());
      return std::sqrt(radial * radial + axial * axial);
    }
    case ClearanceShape::Kind::kBox:
      break;
  }
  return (p.cwiseAbs() - shape.half).cwiseMax(0.0).norm();
}

}  // namespace detail
}  // namespace sixdof_core
