#pragma once

// The occupancy map of MoveIt's perception pipeline: an OctoMap octree of what depth sensors saw, and the
// padded-shape mask that keeps the robot's own links and known objects out of it. The octree library stays
// behind the pimpl; a CollisionScene takes a map (setOccupancyMap) and collides robot bodies against its
// occupied cells.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/collision.h"
#include "sixdof_core/geometry.h"

namespace sixdof_core {

namespace detail {
struct OccupancyMapAccess;
}  // namespace detail

// One occupied leaf of the map: an axis-aligned cube.
struct OccupiedCell {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double size = 0.0;
};

// A probabilistic occupancy octree (OctoMap's OcTree with its default hit/miss probabilities and clamping),
// in one fixed frame. Copies are deep.
class OccupancyMap {
 public:
  // Throws std::invalid_argument unless resolution (the edge of the smallest cell, m) is finite and > 0.
  explicit OccupancyMap(double resolution);
  ~OccupancyMap();
  OccupancyMap(const OccupancyMap& other);
  OccupancyMap& operator=(const OccupancyMap& other);
  OccupancyMap(OccupancyMap&&) noexcept;
  OccupancyMap& operator=(OccupancyMap&&) noexcept;

  double resolution() const;

  // One depth cloud seen from `origin` (everything in the map's frame), as octomap's insertPointCloud with
  // discretization and MoveIt's PointCloudOctomapUpdater do it: one ray per distinct endpoint cell.
  //   hits:    measured surface points: the cells along each ray become freer, the endpoint cell more occupied.
  //   clipped: directions whose measurement lies beyond the sensor's range, given as the point on the ray at
  //            max_range: the ray up to it clears, its end is not marked.
  //   masked:  points on the robot or on a known object: the ray clears, and the endpoint cell is set free
  //            (clamped), so the robot's own body never lingers in the map after it moves.
  // A cell a hit lands on is not cleared by another ray of the same cloud. Non-finite points are ignored.
  void insertScan(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& hits,
                  const std::vector<Eigen::Vector3d>& clipped, const std::vector<Eigen::Vector3d>& masked);

  void clear();
  bool empty() const;  // no occupied cell
  bool isOccupied(const Eigen::Vector3d& point) const;
  std::vector<OccupiedCell> occupiedCells() const;
  // Bounds of the occupied cells (both zero and false when there are none).
  bool occupiedBounds(Eigen::Vector3d* min, Eigen::Vector3d* max) const;
  // OctoMap's binary stream of the tree (OcTree::writeBinaryData: occupied/free bits, no header), what an
  // octomap_msgs/Octomap with binary true and id "OcTree" carries.
  std::string binaryData() const;

 private:
  friend struct detail::OccupancyMapAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Padded solids whose points a depth sensor must not mark occupied (MoveIt's point containment ShapeMask): the
// robot's links, attached objects and known world objects. Each shape grows by `scale` about its origin, then
// by `padding` (m). Boxes, spheres and cylinders are exact; a mesh is the oriented bounding box of its padded
// vertices (a little more than the mesh's hull, which MoveIt masks, never less).
class ShapeMask {
 public:
  // Throws std::invalid_argument unless scale > 0 and padding >= 0 (both finite).
  ShapeMask(double scale, double padding);
  ~ShapeMask();
  ShapeMask(ShapeMask&&) noexcept;
  ShapeMask& operator=(ShapeMask&&) noexcept;

  // Adds a shape at `pose` (the frame the points will be given in). kInvalidShape / kMeshLoadFailed otherwise.
  SceneStatus addShape(const Shape& shape, const Eigen::Isometry3d& pose);
  std::size_t size() const;
  bool contains(const Eigen::Vector3d& point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixdof_core
