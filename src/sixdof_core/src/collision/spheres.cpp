#include "spheres.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

namespace sixdof_core {
namespace detail {
namespace {

using Points = std::vector<Eigen::Vector3d>;

// The grid's cell edge (m) where a shape allows it, and the most cells one shape gets (larger cells then). A sphere
// around a cell part overshoots the surface by a fraction of the cell: this trades the pre-check's tightness
// against its cost.
constexpr double kCellSize = 0.010;
constexpr int kMaxCells = 1000;
// Added to every radius (m): rounding in the section points and the 2D hulls.
constexpr double kRadiusSafety = 1e-9;
// Sides of the prism around a cylinder.
constexpr int kPrismSides = 16;

Eigen::Vector3i gridCounts(const Eigen::Vector3d& extent) {
  for (double cell = kCellSize;; cell *= 1.1) {
    Eigen::Vector3i n;
    for (int i = 0; i < 3; ++i) n[i] = std::max(1, static_cast<int>(std::ceil(extent[i] / cell - 1e-9)));
    if (n.prod() <= kMaxCells) return n;
  }
}

Sphere enclosingSphere(const Points& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Sphere s;
  s.center = 0.5 * (lo + hi);
  double r2 = 0.0;
  for (const Eigen::Vector3d& p : points) r2 = std::max(r2, (p - s.center).squaredNorm());
  s.radius = std::sqrt(r2) + kRadiusSafety;
  return s;
}

// The vertices of the 2D convex hull (Andrew's monotone chain) of coplanar points, in coordinates u and v.
Points hull2d(Points points, int u, int v) {
  std::sort(points.begin(), points.end(), [u, v](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a[u] < b[u] || (a[u] == b[u] && a[v] < b[v]);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto cross = [u, v](const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return (a[u] - o[u]) * (b[v] - o[v]) - (a[v] - o[v]) * (b[u] - o[u]);
  };
  Points hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Spheres covering conv(points) cut into counts[axis] slabs between lo and hi along `axis`, then along the next
// axes. A convex hull's section by a plane is the hull of the points on the plane and of where the segments between
// the points cross it; so conv(points) within a slab is the hull of the points inside it and of its two sections.
void coverHull(const Points& points, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               const Eigen::Vector3i& counts, int axis, std::vector<Sphere>* out) {
  if (points.empty()) return;
  if (axis == 3) {
    out->push_back(enclosingSphere(points));
    return;
  }
  const int n = counts[axis];
  std::vector<double> planes(n + 1);
  for (int k = 0; k <= n; ++k) planes[k] = k == n ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * k / n;
  std::vector<Points> sections(n + 1);
  for (int k = 1; k < n; ++k) {
    const double t = planes[k];
    Points section;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double di = points[i][axis] - t;
      if (di == 0.0) section.push_back(points[i]);
      for (std::size_t j = i + 1; j < points.size(); ++j) {
        const double dj = points[j][axis] - t;
        if ((di < 0.0 && dj > 0.0) || (di > 0.0 && dj < 0.0)) {
          Eigen::Vector3d p = points[i] + (di / (di - dj)) * (points[j] - points[i]);
          p[axis] = t;
          section.push_back(p);
        }
      }
    }
    sections[k] = hull2d(std::move(section), (axis + 1) % 3, (axis + 2) % 3);
  }
  for (int k = 0; k < n; ++k) {
    Points slab = sections[k];
    slab.insert(slab.end(), sections[k + 1].begin(), sections[k + 1].end());
    // The outer slabs are open outwards: a section point may lie a rounding error beyond lo or hi.
    for (const Eigen::Vector3d& p : points) {
      if ((k == 0 || p[axis] >= planes[k]) && (k + 1 == n || p[axis] <= planes[k + 1])) slab.push_back(p);
    }
    coverHull(slab, lo, hi, counts, axis + 1, out);
  }
}

// The part of a polygon on one side of the plane x[axis] = bound (keep_below: x[axis] <= bound).
Points clip(const Points& polygon, int axis, double bound, bool keep_below) {
  Points out;
  const auto inside = [&](const Eigen::Vector3d& p) { return keep_below ? p[axis] <= bound : p[axis] >= bound; };
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      Eigen::Vector3d p = a + ((bound - a[axis]) / (b[axis] - a[axis])) * (b - a);
      p[axis] = bound;
      out.push_back(p);
    }
  }
  return out;
}

// Spheres covering triangles (a surface): per grid cell, the sphere around the triangles clipped to the cell.
void coverSurface(const std::vector<std::array<Eigen::Vector3d, 3>>& triangles, const Eigen::Vector3d& lo,
                  const Eigen::Vector3d& hi, const Eigen::Vector3i& counts, std::vector<Sphere>* out) {
  const Eigen::Vector3d step = (hi - lo).cwiseQuotient(counts.cast<double>());
  for (int i = 0; i < counts[0]; ++i) {
    for (int j = 0; j < counts[1]; ++j) {
      for (int k = 0; k < counts[2]; ++k) {
        const Eigen::Vector3i cell(i, j, k);
        Eigen::Vector3d cell_lo, cell_hi;
        for (int a = 0; a < 3; ++a) {
          cell_lo[a] = cell[a] == 0 ? lo[a] : lo[a] + step[a] * cell[a];
          cell_hi[a] = cell[a] + 1 == counts[a] ? hi[a] : lo[a] + step[a] * (cell[a] + 1);
        }
        Points points;
        for (const auto& t : triangles) {
          Points polygon(t.begin(), t.end());
          for (int a = 0; a < 3 && !polygon.empty(); ++a) {
            polygon = clip(clip(polygon, a, cell_lo[a], false), a, cell_hi[a], true);
          }
          points.insert(points.end(), polygon.begin(), polygon.end());
        }
        if (!points.empty()) out->push_back(enclosingSphere(points));
      }
    }
  }
}

}  // namespace

std::vector<Sphere> coveringSpheres(const fcl::CollisionGeometryd& geometry, const Obb& obb) {
  std::vector<Sphere> spheres;
  Points solid;  // a convex solid's points (geometry frame)
  std::vector<std::array<Eigen::Vector3d, 3>> surface;
  switch (geometry.getNodeType()) {
    case fcl::GEOM_SPHERE:
      spheres.push_back(Sphere{Eigen::Vector3d::Zero(), static_cast<const fcl::Sphered&>(geometry).radius});
      return spheres;
    case fcl::GEOM_BOX: {
      const Eigen::Vector3d half = 0.5 * static_cast<const fcl::Boxd&>(geometry).side;
      for (int c = 0; c < 8; ++c) {
        solid.emplace_back(c & 1 ? half.x() : -half.x(), c & 2 ? half.y() : -half.y(), c & 4 ? half.z() : -half.z());
      }
      break;
    }
    case fcl::GEOM_CYLINDER: {
      const auto& cylinder = static_cast<const fcl::Cylinderd&>(geometry);
      const double r = cylinder.radius / std::cos(M_PI / kPrismSides);  // the prism's sides touch the cylinder
      for (int k = 0; k < kPrismSides; ++k) {
        const double angle = 2.0 * M_PI * k / kPrismSides;
        for (double z : {-0.5 * cylinder.lz, 0.5 * cylinder.lz}) {
          solid.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
        }
      }
      break;
    }
    case fcl::GEOM_CONVEX:
      solid = static_cast<const fcl::Convexd&>(geometry).getVertices();
      break;
    case fcl::BV_OBBRSS: {
      const auto& bvh = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(geometry);
      for (int t = 0; t < bvh.num_tris; ++t) {
        const fcl::Triangle& tri = bvh.tri_indices[t];
        surface.push_back({bvh.vertices[tri[0]], bvh.vertices[tri[1]], bvh.vertices[tri[2]]});
      }
      break;
    }
    default:  // any other geometry: its oriented box
      for (int c = 0; c < 8; ++c) {
        solid.push_back(obb.center + obb.axes * Eigen::Vector3d(c & 1 ? obb.half.x() : -obb.half.x(),
                                                                c & 2 ? obb.half.y() : -obb.half.y(),
                                                                c & 4 ? obb.half.z() : -obb.half.z()));
      }
      break;
  }
  // Work in the oriented box's frame, on the points' own bounds there.
  const auto local = [&obb](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return obb.axes.transpose() * (p - obb.center);
  };
  for (Eigen::Vector3d& p : solid) p = local(p);
  for (auto& t : surface) {
    for (Eigen::Vector3d& p : t) p = local(p);
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Eigen::Vector3d& p : solid) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (const auto& t : surface) {
    for (const Eigen::Vector3d& p : t) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  if (!(lo.array() <= hi.array()).all()) return spheres;
  const Eigen::Vector3i counts = gridCounts(hi - lo);
  if (surface.empty()) {
    coverHull(solid, lo, hi, counts, 0, &spheres);
  } else {
    coverSurface(surface, lo, hi, counts, &spheres);
  }
  for (Sphere& s : spheres) s.center = obb.center + obb.axes * s.center;
  return spheres;
}

std::vector<Sphere> coveringSpheres(const std::shared_ptr<fcl::CollisionGeometryd>& geometry, const Obb& obb) {
  const fcl::NODE_TYPE type = geometry->getNodeType();
  if (type != fcl::GEOM_CONVEX && type != fcl::BV_OBBRSS) return coveringSpheres(*geometry, obb);
  // Keyed by the geometry itself (held, so that its address stays its own).
  static std::mutex mutex;
  static std::map<const fcl::CollisionGeometryd*,
                  std::pair<std::shared_ptr<fcl::CollisionGeometryd>, std::vector<Sphere>>>
      cache;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(geometry.get());
    if (it != cache.end()) return it->second.second;
  }
  std::vector<Sphere> spheres = coveringSpheres(*geometry, obb);
  std::lock_guard<std::mutex> lock(mutex);
  cache.emplace(geometry.get(), std::make_pair(geometry, spheres));
  return spheres;
}

namespace {

int buildNode(std::vector<Sphere>* spheres, std::size_t begin, std::size_t end, std::vector<SphereNode>* nodes) {
  const int index = static_cast<int>(nodes->size());
  nodes->emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Eigen::Vector3d centre_lo = lo, centre_hi = hi;
  for (std::size_t i = begin; i < end; ++i) {
    const Sphere& s = (*spheres)[i];
    lo = lo.cwiseMin(s.center - Eigen::Vector3d::Constant(s.radius));
    hi = hi.cwiseMax(s.center + Eigen::Vector3d::Constant(s.radius));
    centre_lo = centre_lo.cwiseMin(s.center);
    centre_hi = centre_hi.cwiseMax(s.center);
  }
  SphereNode node;
  node.center = 0.5 * (lo + hi);
  for (std::size_t i = begin; i < end; ++i) {
    const Sphere& s = (*spheres)[i];
    node.radius = std::max(node.radius, (s.center - node.center).norm() + s.radius + kRadiusSafety);
    node.reach = std::max(node.reach, s.center.norm() + s.radius);
  }
  if (end - begin > 1) {
    int axis = 0;
    (centre_hi - centre_lo).maxCoeff(&axis);
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(spheres->begin() + begin, spheres->begin() + mid, spheres->begin() + end,
                     [axis](const Sphere& a, const Sphere& b) { return a.center[axis] < b.center[axis]; });
    node.left = buildNode(spheres, begin, mid, nodes);
    node.right = buildNode(spheres, mid, end, nodes);
  } else {
    node.center = (*spheres)[begin].center;
    node.radius = (*spheres)[begin].radius;
  }
  (*nodes)[index] = node;
  return index;
}

}  // namespace

std::vector<SphereNode> buildSphereTree(std::vector<Sphere> spheres) {
  std::vector<SphereNode> nodes;
  if (spheres.empty()) return nodes;
  nodes.reserve(2 * spheres.size());
  buildNode(&spheres, 0, spheres.size(), &nodes);
  return nodes;
}

ClearanceShape clearanceShape(const fcl::CollisionGeometryd& geometry, const Obb& obb, const Eigen::Isometry3d& tf) {
  ClearanceShape shape;
  shape.center = tf.translation();
  shape.rotation = tf.linear();
  switch (geometry.getNodeType()) {
    case fcl::GEOM_BOX:
      shape.half = 0.5 * static_cast<const fcl::Boxd&>(geometry).side;
      return shape;
    case fcl::GEOM_SPHERE:
      shape.kind = ClearanceShape::Kind::kSphere;
      shape.half.x() = static_cast<const fcl::Sphered&>(geometry).radius;
      return shape;
    case fcl::GEOM_CYLINDER: {
      const auto& cylinder = static_cast<const fcl::Cylinderd&>(geometry);
      shape.kind = ClearanceShape::Kind::kCylinder;
      shape.half = Eigen::Vector3d(cylinder.radius, cylinder.radius, 0.5 * cylinder.lz);
      return shape;
    }
    default:
      break;
  }
  shape.center = tf * obb.center;
  shape.rotation = tf.linear() * obb.axes;
  shape.half = obb.half;
  return shape;
}

ClearanceShape clearanceBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  ClearanceShape shape;
  shape.center = 0.5 * (min + max);
  shape.half = 0.5 * (max - min);
  return shape;
}

}  // namespace detail
}  // namespace sixdof_core
