#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/narrowphase/contact.h>

#include "fcl_geometry.h"

namespace sixdof_core {
namespace detail {

// Collides two shapes (the OBB prefilter first, then FCL); fills contacts (body1 -> body2 normals) when asked.
bool narrowPhase(const ShapeInstance& s1, const Eigen::Isometry3d& tf1, const ShapeInstance& s2,
                 const Eigen::Isometry3d& tf2, std::size_t max_contacts, std::vector<fcl::Contactd>* contacts);

struct PairDistance {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d p2 = Eigen::Vector3d::Zero();
};

// Signed distance of two shapes: negative is the deepest penetration, with both points at its contact.
PairDistance shapeDistance(const ShapeInstance& s1, const Eigen::Isometry3d& tf1, const ShapeInstance& s2,
                           const Eigen::Isometry3d& tf2);

// Boxes farther apart than the best distance cannot improve it; while the best is a penetration, only
// overlapping boxes can hold a deeper one.
inline bool prunable(double box_distance, double best) {
  return best <= 0.0 ? box_distance > 0.0 : box_distance >= best;
}

}  // namespace detail
}  // namespace sixdof_core
