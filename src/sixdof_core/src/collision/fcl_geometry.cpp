#include "fcl_geometry.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <array>
#include <cmath>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <limits>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

#include "sixdof_core/mesh_loader.h"

namespace sixdof_core {
namespace detail {
namespace {

// The smaller (by volume) of the box along the shape's frame and the box along the points' principal axes.
Obb pointsObb(const std::vector<Eigen::Vector3d>& points) {
  Obb best;
  if (points.empty()) return best;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : points) mean += v;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& v : points) covariance += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
  double best_volume = std::numeric_limits<double>::infinity();
  for (const Eigen::Matrix3d& axes : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), pca.eigenvectors()}) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (const auto& v : points) {
      const Eigen::Vector3d p = axes.transpose() * v;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const Eigen::Vector3d half = 0.5 * (hi - lo);
    const double volume = half.prod();
    if (volume < best_volume) {
      best_volume = volume;
      best.axes = axes;
      best.center = axes * (0.5 * (hi + lo));
      best.half = half;
    }
  }
  return best;
}

GeometryPtr meshGeometry(const MeshData& mesh, double scale, double padding) {
  auto vertices = std::make_shared<std::vector<Eigen::Vector3d>>();
  vertices->reserve(mesh.vertices.size());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) {
    vertices->push_back(v * scale);
    centroid += v * scale;
  }
  centroid /= static_cast<double>(mesh.vertices.size());
  // Convex meshes get outward winding from the centroid; other meshes keep the file's winding.
  std::vector<std::array<int, 3>> triangles = mesh.triangles;
  if (mesh.convex) {
    for (auto& t : triangles) {
      const Eigen::Vector3d& a = (*vertices)[t[0]];
      const Eigen::Vector3d n = ((*vertices)[t[1]] - a).cross((*vertices)[t[2]] - a);
      if (n.dot(a - centroid) < 0.0) std::swap(t[1], t[2]);
    }
  }
  if (padding > 0.0) {
    // Each vertex moves so that every incident face plane moves out by the padding (least squares over
    // the face normals: exact where at most three planes meet, as on boxes and CAD hulls), so the padded
    // mesh contains the surface offset by the padding instead of shrinking towards the corners.
    std::vector<Eigen::Matrix3d> normal_sum(vertices->size(), Eigen::Matrix3d::Zero());
    std::vector<Eigen::Vector3d> rhs(vertices->size(), Eigen::Vector3d::Zero());
    for (const auto& t : triangles) {
      const Eigen::Vector3d& a = (*vertices)[t[0]];
      Eigen::Vector3d n = ((*vertices)[t[1]] - a).cross((*vertices)[t[2]] - a);
      if (n.norm() < 1e-15) continue;
      n.normalize();
      for (int k : t) {
        normal_sum[k] += n * n.transpose();
        rhs[k] += n;
      }
    }
    for (std::size_t k = 0; k < vertices->size(); ++k) {
      Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d> solver(normal_sum[k]);
      solver.setThreshold(1e-6);
      (*vertices)[k] += padding * solver.solve(rhs[k]);
    }
  }
  if (mesh.convex) {
    auto faces = std::make_shared<std::vector<int>>();
    faces->reserve(triangles.size() * 4);
    for (const auto& t : triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    auto convex = std::make_shared<fcl::Convexd>(vertices, static_cast<int>(triangles.size()), faces);
    convex->computeLocalAABB();
    return convex;
  }
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Triangle> fcl_triangles;
  fcl_triangles.reserve(triangles.size());
  for (const auto& t : triangles) fcl_triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(static_cast<int>(fcl_triangles.size()), static_cast<int>(vertices->size()));
  bvh->addSubModel(*vertices, fcl_triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

}  // namespace

// Bounding box of an FCL geometry built by makeGeometry() (primitives exactly, meshes from their vertices).
Obb geometryObb(const fcl::CollisionGeometryd& geometry) {
  Obb obb;
  switch (geometry.getNodeType()) {
    case fcl::GEOM_BOX:
      obb.half = 0.5 * static_cast<const fcl::Boxd&>(geometry).side;
      return obb;
    case fcl::GEOM_SPHERE:
      obb.half.setConstant(static_cast<const fcl::Sphered&>(geometry).radius);
      return obb;
    case fcl::GEOM_CYLINDER: {
      const auto& c = static_cast<const fcl::Cylinderd&>(geometry);
      obb.half = Eigen::Vector3d(c.radius, c.radius, 0.5 * c.lz);
      return obb;
    }
    case fcl::GEOM_CONVEX:
      return pointsObb(static_cast<const fcl::Convexd&>(geometry).getVertices());
    case fcl::BV_OBBRSS: {
      const auto& bvh = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(geometry);
      return pointsObb(std::vector<Eigen::Vector3d>(bvh.vertices, bvh.vertices + bvh.num_vertices));
    }
    default:
      break;
  }
  // Any other geometry: its local AABB.
  obb.center = geometry.aabb_local.center();
  obb.half = 0.5 * (geometry.aabb_local.max_ - geometry.aabb_local.min_);
  return obb;
}

fcl::AABBd worldAabb(const fcl::CollisionGeometryd& geometry, const Eigen::Isometry3d& tf) {
  const fcl::AABBd& local = geometry.aabb_local;
  const Eigen::Vector3d center = tf * local.center();
  const Eigen::Vector3d extent = tf.linear().cwiseAbs() * ((local.max_ - local.min_) * 0.5);
  return fcl::AABBd(center - extent, center + extent);
}

// Builds the FCL geometry of a shape scaled about its origin and then padded.
GeometryPtr makeGeometry(const Shape& shape, double scale, double padding, SceneStatus* status) {
  GeometryPtr geometry;
  switch (shape.type) {
    case Shape::Type::kBox:
      if (!shape.box_size.allFinite() || (shape.box_size.array() <= 0.0).any()) {
        *status = error(SceneStatusCode::kInvalidShape, "box size must be positive and finite");
        return nullptr;
      }
      geometry = std::make_shared<fcl::Boxd>(shape.box_size * scale + Eigen::Vector3d::Constant(2.0 * padding));
      break;
    case Shape::Type::kSphere:
      if (!std::isfinite(shape.radius) || shape.radius <= 0.0) {
        *status = error(SceneStatusCode::kInvalidShape, "sphere radius must be positive and finite");
        return nullptr;
      }
      geometry = std::make_shared<fcl::Sphered>(shape.radius * scale + padding);
      break;
    case Shape::Type::kCylinder:
      if (!std::isfinite(shape.radius) || shape.radius <= 0.0 || !std::isfinite(shape.length) || shape.length <= 0.0) {
        *status = error(SceneStatusCode::kInvalidShape, "cylinder radius and length must be positive and finite");
        return nullptr;
      }
      geometry =
          std::make_shared<fcl::Cylinderd>(shape.radius * scale + padding, shape.length * scale + 2.0 * padding);
      break;
    case Shape::Type::kMesh: {
      // Built geometries are immutable, so one per (file, scales, padding) is shared by every scene.
      static std::mutex mutex;
      static std::map<std::tuple<std::string, double, double, double, double, double>, GeometryPtr> cache;
      const auto key = std::make_tuple(shape.mesh_path, shape.mesh_scale.x(), shape.mesh_scale.y(),
                                       shape.mesh_scale.z(), scale, padding);
      {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
      }
      const MeshLoadResult loaded = loadMesh(shape.mesh_path, shape.mesh_scale);
      if (!loaded.ok()) {
        *status = error(SceneStatusCode::kMeshLoadFailed, loaded.message);
        return nullptr;
      }
      geometry = meshGeometry(*loaded.mesh, scale, padding);
      std::lock_guard<std::mutex> lock(mutex);
      cache.emplace(key, geometry);
      return geometry;
    }
  }
  geometry->computeLocalAABB();
  return geometry;
}

}  // namespace detail
}  // namespace sixdof_core
