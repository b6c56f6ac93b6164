#include "sixdof_core/occupancy_map.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fcl_geometry.h"
#include "occupancy_map_impl.h"

namespace sixdof_core {

namespace {

octomap::point3d toPoint(const Eigen::Vector3d& p) {
  return octomap::point3d(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
}

void insertKeys(const octomap::OcTree& tree, const std::vector<Eigen::Vector3d>& points, octomap::KeySet* keys) {
  octomap::OcTreeKey key;
  for (const auto& p : points) {
    if (p.allFinite() && tree.coordToKeyChecked(toPoint(p), key)) keys->insert(key);
  }
}

}  // namespace

OccupancyMap::OccupancyMap(double resolution) : impl_(std::make_unique<Impl>()) {
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    throw std::invalid_argument("OccupancyMap: resolution must be finite and > 0, got " + std::to_string(resolution));
  }
  impl_->tree = std::make_shared<octomap::OcTree>(resolution);
}

OccupancyMap::~OccupancyMap() = default;
OccupancyMap::OccupancyMap(const OccupancyMap& other) : impl_(std::make_unique<Impl>()) {
  impl_->tree = std::make_shared<octomap::OcTree>(*other.impl_->tree);
}
OccupancyMap& OccupancyMap::operator=(const OccupancyMap& other) {
  if (this != &other) impl_->tree = std::make_shared<octomap::OcTree>(*other.impl_->tree);
  return *this;
}
OccupancyMap::OccupancyMap(OccupancyMap&&) noexcept = default;
OccupancyMap& OccupancyMap::operator=(OccupancyMap&&) noexcept = default;

double OccupancyMap::resolution() const { return impl_->tree->getResolution(); }

std::string OccupancyMap::binaryData() const {
  std::ostringstream out;
  impl_->tree->writeBinaryData(out);
  return out.str();
}

void OccupancyMap::insertScan(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& hits,
                              const std::vector<Eigen::Vector3d>& clipped, const std::vector<Eigen::Vector3d>& masked) {
  octomap::OcTree& tree = *impl_->tree;
  if (!origin.allFinite()) return;
  const octomap::point3d sensor = toPoint(origin);
  octomap::KeySet occupied, clip, model, free;
  insertKeys(tree, hits, &occupied);
  insertKeys(tree, clipped, &clip);
  insertKeys(tree, masked, &model);
  // A cell holding any part of the robot or a known object is theirs, even if a point of something else
  // falls into it too: the map must never hold the robot.
  for (const auto& key : model) occupied.erase(key);
  octomap::KeyRay ray;
  for (const octomap::KeySet* ends : {&occupied, &clip, &model}) {
    for (const auto& key : *ends) {
      if (tree.computeRayKeys(sensor, tree.keyToCoord(key), ray)) free.insert(ray.begin(), ray.end());
    }
  }
  for (const auto& key : free) {
    if (!occupied.count(key) && !model.count(key)) tree.updateNode(key, false, true);
  }
  for (const auto& key : occupied) tree.updateNode(key, true, true);
  const float to_minimum = tree.getClampingThresMinLog() - tree.getClampingThresMaxLog();
  for (const auto& key : model) tree.updateNode(key, to_minimum, true);
  tree.updateInnerOccupancy();
}

void OccupancyMap::clear() { impl_->tree->clear(); }

bool OccupancyMap::empty() const {
  const octomap::OcTree& tree = *impl_->tree;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (tree.isNodeOccupied(*it)) return false;
  }
  return true;
}

bool OccupancyMap::isOccupied(const Eigen::Vector3d& point) const {
  if (!point.allFinite()) return false;
  const octomap::OcTreeNode* node = impl_->tree->search(toPoint(point));
  return node != nullptr && impl_->tree->isNodeOccupied(node);
}

std::vector<OccupiedCell> OccupancyMap::occupiedCells() const {
  const octomap::OcTree& tree = *impl_->tree;
  std::vector<OccupiedCell> cells;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const octomap::point3d c = it.getCoordinate();
    cells.push_back(OccupiedCell{Eigen::Vector3d(c.x(), c.y(), c.z()), it.getSize()});
  }
  return cells;
}

bool OccupancyMap::occupiedBounds(Eigen::Vector3d* min, Eigen::Vector3d* max) const {
  const octomap::OcTree& tree = *impl_->tree;
  bool any = false;
  *min = Eigen::Vector3d::Zero();
  *max = Eigen::Vector3d::Zero();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const octomap::point3d c = it.getCoordinate();
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * it.getSize());
    const Eigen::Vector3d center(c.x(), c.y(), c.z());
    *min = any ? min->cwiseMin(center - half) : Eigen::Vector3d(center - half);
    *max = any ? max->cwiseMax(center + half) : Eigen::Vector3d(center + half);
    any = true;
  }
  return any;
}

// ShapeMask

namespace {

struct MaskShape {
  enum class Kind { kBox, kSphere, kCylinder, kBoundingBox };
  Kind kind = Kind::kBox;
  Eigen::Isometry3d world_to_shape = Eigen::Isometry3d::Identity();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // bounding sphere, in the mask's frame
  double bound_sq = 0.0;
  Eigen::Vector3d half = Eigen::Vector3d::Zero();    // box / bounding box half extents; cylinder (r, r, l/2)
  double radius = 0.0;                               // sphere, cylinder
  Eigen::Vector3d box_center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d box_axes = Eigen::Matrix3d::Identity();

  bool contains(const Eigen::Vector3d& point) const {
    if ((point - center).squaredNorm() > bound_sq) return false;
    const Eigen::Vector3d p = world_to_shape * point;
    switch (kind) {
      case Kind::kBox:
        return (p.cwiseAbs().array() <= half.array()).all();
      case Kind::kSphere:
        return p.squaredNorm() <= radius * radius;
      case Kind::kCylinder:
        return std::abs(p.z()) <= half.z() && p.head<2>().squaredNorm() <= radius * radius;
      case Kind::kBoundingBox:
        return ((box_axes.transpose() * (p - box_center)).cwiseAbs().array() <= half.array()).all();
    }
    return false;
  }
};

}  // namespace

struct ShapeMask::Impl {
  double scale = 1.0;
  double padding = 0.0;
  std::vector<MaskShape> shapes;
};

ShapeMask::ShapeMask(double scale, double padding) : impl_(std::make_unique<Impl>()) {
  if (!std::isfinite(scale) || scale <= 0.0) throw std::invalid_argument("ShapeMask: scale must be finite and > 0");
  if (!std::isfinite(padding) || padding < 0.0) {
    throw std::invalid_argument("ShapeMask: padding must be finite and >= 0");
  }
  impl_->scale = scale;
  impl_->padding = padding;
}

ShapeMask::~ShapeMask() = default;
ShapeMask::ShapeMask(ShapeMask&&) noexcept = default;
ShapeMask& ShapeMask::operator=(ShapeMask&&) noexcept = default;

SceneStatus ShapeMask::addShape(const Shape& shape, const Eigen::Isometry3d& pose) {
  if (!pose.matrix().allFinite()) return detail::error(SceneStatusCode::kInvalidValue, "mask shape pose is not finite");
  // The collision geometry builder validates the shape and pads meshes the way the planning scene does.
  SceneStatus status;
  const detail::GeometryPtr geometry = detail::makeGeometry(shape, impl_->scale, impl_->padding, &status);
  if (!geometry) return status;
  MaskShape mask;
  mask.world_to_shape = pose.inverse();
  Eigen::Vector3d local_center = Eigen::Vector3d::Zero();
  double bound = 0.0;
  switch (shape.type) {
    case Shape::Type::kBox:
      mask.kind = MaskShape::Kind::kBox;
      mask.half = 0.5 * shape.box_size * impl_->scale + Eigen::Vector3d::Constant(impl_->padding);
      bound = mask.half.norm();
      break;
    case Shape::Type::kSphere:
      mask.kind = MaskShape::Kind::kSphere;
      mask.radius = shape.radius * impl_->scale + impl_->padding;
      bound = mask.radius;
      break;
    case Shape::Type::kCylinder:
      mask.kind = MaskShape::Kind::kCylinder;
      mask.radius = shape.radius * impl_->scale + impl_->padding;
      mask.half = Eigen::Vector3d(mask.radius, mask.radius, 0.5 * shape.length * impl_->scale + impl_->padding);
      bound = mask.half.norm();
      break;
    case Shape::Type::kMesh: {
      // The padded mesh's oriented bounding box: a superset of its hull (MoveIt masks the hull). A mesh's
      // triangles need not cover its hull (the convexity test looks at the vertices), so no face-plane test.
      const detail::Obb obb = detail::geometryObb(*geometry);
      mask.kind = MaskShape::Kind::kBoundingBox;
      mask.box_center = obb.center;
      mask.box_axes = obb.axes;
      mask.half = obb.half;
      local_center = obb.center;
      bound = obb.half.norm();
      break;
    }
  }
  mask.center = pose * local_center;
  mask.bound_sq = bound * bound;
  impl_->shapes.push_back(std::move(mask));
  return SceneStatus();
}

std::size_t ShapeMask::size() const { return impl_->shapes.size(); }

bool ShapeMask::contains(const Eigen::Vector3d& point) const {
  for (const auto& shape : impl_->shapes) {
    if (shape.contains(point)) return true;
  }
  return false;
}

}  // namespace sixdof_core
