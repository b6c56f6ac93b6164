#include "narrow_phase.h"

#include <cmath>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "obb.h"

namespace sixdof_core {
namespace detail {

// Collides two shapes; fills contacts (body1 -> body2 normals) when asked.
bool narrowPhase(const ShapeInstance& s1, const Eigen::Isometry3d& tf1, const ShapeInstance& s2,
                 const Eigen::Isometry3d& tf2, std::size_t max_contacts, std::vector<fcl::Contactd>* contacts) {
  if (!obbOverlap(s1.obb, tf1, s2.obb, tf2)) return false;
  fcl::CollisionRequestd request(contacts ? max_contacts : 1, contacts != nullptr);
  fcl::CollisionResultd result;
  fcl::collide(s1.geometry.get(), tf1, s2.geometry.get(), tf2, request, result);
  if (!result.isCollision()) return false;
  if (contacts) {
    result.getContacts(*contacts);
    // FCL answers a shape-vs-mesh query as mesh-vs-shape; put the pair back in the caller's order.
    for (auto& c : *contacts) {
      if (c.o1 != s1.geometry.get()) {
        std::swap(c.o1, c.o2);
        std::swap(c.b1, c.b2);
        c.normal = -c.normal;
      }
      // FCL 0.7's sphere-triangle test reports depths as negative numbers.
      c.penetration_depth = std::abs(c.penetration_depth);
    }
  }
  return true;
}

PairDistance shapeDistance(const ShapeInstance& s1, const Eigen::Isometry3d& tf1, const ShapeInstance& s2,
                           const Eigen::Isometry3d& tf2) {
  PairDistance out;
  fcl::DistanceRequestd request(true);
  fcl::DistanceResultd result;
  fcl::distance(s1.geometry.get(), tf1, s2.geometry.get(), tf2, request, result);
  // As in narrowPhase, a shape-vs-mesh answer comes back in mesh-vs-shape order.
  const bool swapped = result.o1 != s1.geometry.get();
  Eigen::Vector3d near1 = result.nearest_points[swapped ? 1 : 0];
  Eigen::Vector3d near2 = result.nearest_points[swapped ? 0 : 1];
  // FCL 0.7 gives sphere-vs-mesh nearest points in each object's own frame (every other pairing: world).
  const fcl::NODE_TYPE type1 = s1.geometry->getNodeType(), type2 = s2.geometry->getNodeType();
  if ((type1 == fcl::GEOM_SPHERE && type2 == fcl::BV_OBBRSS) ||
      (type1 == fcl::BV_OBBRSS && type2 == fcl::GEOM_SPHERE)) {
    near1 = tf1 * near1;
    near2 = tf2 * near2;
  }
  if (result.min_distance > 0.0) {
    out.distance = result.min_distance;
    out.p1 = near1;
    out.p2 = near2;
    return out;
  }
  // FCL's distance gives no penetration depth; the contacts of a collision query do.
  std::vector<fcl::Contactd> contacts;
  out.distance = 0.0;
  if (narrowPhase(s1, tf1, s2, tf2, 16, &contacts)) {
    for (const auto& c : contacts) {
      if (-c.penetration_depth <= out.distance) {
        out.distance = -c.penetration_depth;
        out.p1 = c.pos;
        out.p2 = c.pos;
      }
    }
  } else {
    out.p1 = near1;
    out.p2 = near2;
  }
  return out;
}

}  // namespace detail
}  // namespace sixdof_core
