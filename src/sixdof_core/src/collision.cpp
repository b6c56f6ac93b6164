#include "sixdof_core/collision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "collision/scene_impl.h"

// The public CollisionScene: construction, the allowed collision matrix, padding and scale, objects and the
// three queries. Geometry building is in collision/fcl_geometry.cpp, the OBB prefilter in collision/obb.cpp,
// the shape-pair tests in collision/narrow_phase.cpp and the scene's pair walks in collision/scene_impl.cpp; the
// sphere pre-check (precheckMotion) is in collision/precheck.cpp, its spheres in collision/spheres.cpp.

namespace sixdof_core {

using detail::Body;
using detail::coveringSpheres;
using detail::error;
using detail::geometryObb;
using detail::GeometryPtr;
using detail::makeGeometry;
using detail::prunable;
using detail::shapeDistance;
using detail::ShapeInstance;
using detail::ShapePose;

namespace {

std::string describe(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::kBox:
      return "box";
    case Shape::Type::kSphere:
      return "sphere";
    case Shape::Type::kCylinder:
      return "cylinder";
    case Shape::Type::kMesh:
      return "mesh '" + shape.mesh_path + "'";
  }
  return "shape";
}

SceneStatus buildShapes(Body* body) {
  body->shapes.clear();
  for (const PlacedShape& placed : body->source) {
    SceneStatus status;
    GeometryPtr geometry = makeGeometry(placed.shape, body->scale, body->padding, &status);
    if (!geometry) {
      status.message = "'" + body->name + "': " + describe(placed.shape) + ": " + status.message;
      return status;
    }
    ShapeInstance shape{geometry, placed.origin, geometryObb(*geometry), placed.origin.matrix().isIdentity(0.0), {}};
    // Only robot bodies move, so only they need the pre-check's spheres (world shapes are measured as they are).
    if (body->type != BodyType::kWorldObject) shape.spheres = coveringSpheres(geometry, shape.obb);
    body->shapes.push_back(std::move(shape));
  }
  return SceneStatus();
}

// Sets a link's padding or scale (`what`, valid when finite and `requirement`) and rebuilds its shapes. An unknown
// link (null body) or an invalid value changes nothing; the old value and shapes stay if the rebuild fails.
SceneStatus setLinkValue(Body* body, const std::string& link_name, const char* what, double Body::*member,
                         double value, bool valid, const char* requirement) {
  if (!body) return error(SceneStatusCode::kUnknownName, std::string(what) + ": unknown link '" + link_name + "'");
  if (!std::isfinite(value) || !valid) {
    return error(SceneStatusCode::kInvalidValue,
                 std::string(what) + " of '" + link_name + "' must be finite and " + requirement);
  }
  const double old = body->*member;
  body->*member = value;
  SceneStatus status = buildShapes(body);
  if (!status.ok()) {
    body->*member = old;
    buildShapes(body);
  }
  return status;
}

// addWorldObject/attachObject: a new object's id is set and not yet the name of a link or another object.
SceneStatus checkNewId(const char* what, const std::string& id, bool name_in_use) {
  if (id.empty()) return error(SceneStatusCode::kInvalidValue, std::string(what) + ": empty id");
  if (name_in_use) {
    return error(SceneStatusCode::kDuplicateName, std::string(what) + " '" + id + "': name already in use");
  }
  return SceneStatus();
}

// moveWorldObject/attachWorldObject/detachObject (`op`): the object was found (`index` >= 0) and the pose that
// places it (`pose_name`) is finite.
SceneStatus checkObjectMove(int index, const char* op, const char* kind, const std::string& id, const char* pose_name,
                            const Eigen::Isometry3d& pose) {
  if (index < 0) return error(SceneStatusCode::kUnknownName, std::string(op) + ": unknown " + kind + " '" + id + "'");
  if (!pose.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, std::string(op) + ": " + pose_name + " '" + id + "' is not finite");
  }
  return SceneStatus();
}

Body objectBody(const std::string& id, BodyType type, const Eigen::Isometry3d& pose,
                const std::vector<PlacedShape>& shapes) {
  Body body;
  body.name = id;
  body.type = type;
  body.pose = pose;
  body.source = shapes;
  return body;
}

// addWorldObject/attachObject: the new object has shapes and a finite pose, then its shapes are built (messages
// start with `what`) and it is appended to `bodies`.
SceneStatus appendBody(Body body, const char* what, std::vector<Body>* bodies) {
  const std::string object = std::string(what) + " '" + body.name + "'";
  if (body.source.empty()) return error(SceneStatusCode::kInvalidShape, object + ": has no shapes");
  if (!body.pose.matrix().allFinite()) return error(SceneStatusCode::kInvalidValue, object + ": pose is not finite");
  SceneStatus status = buildShapes(&body);
  if (!status.ok()) {
    status.message = std::string(what) + " " + status.message;
    return status;
  }
  bodies->push_back(std::move(body));
  return status;
}

// setPadding/setScale: the per-link setter applied to every link, up to the first failure.
template <class SetLink>
SceneStatus setEveryLink(const std::vector<std::string>& link_names, const SetLink& set_link) {
  for (const std::string& name : link_names) {
    SceneStatus status = set_link(name);
    if (!status.ok()) return status;
  }
  return SceneStatus();
}

}  // namespace

CollisionScene::CollisionScene(const std::vector<LinkGeometry>& links,
                               const std::vector<std::pair<std::string, std::string>>& disabled_pairs,
                               const CollisionSceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (!std::isfinite(options.link_padding) || options.link_padding < 0.0) {
    throw std::invalid_argument("CollisionScene: link_padding must be finite and >= 0");
  }
  if (!std::isfinite(options.link_scale) || options.link_scale <= 0.0) {
    throw std::invalid_argument("CollisionScene: link_scale must be finite and > 0");
  }
  for (const LinkGeometry& link : links) {
    if (link.link_name.empty()) throw std::invalid_argument("CollisionScene: a link has an empty name");
    if (!impl_->link_index.emplace(link.link_name, static_cast<int>(impl_->links.size())).second) {
      throw std::invalid_argument("CollisionScene: duplicate link '" + link.link_name + "'");
    }
    Body body;
    body.name = link.link_name;
    body.type = BodyType::kRobotLink;
    body.link = static_cast<int>(impl_->links.size());
    body.source = link.shapes;
    body.padding = options.link_padding;
    body.scale = options.link_scale;
    const SceneStatus status = buildShapes(&body);
    if (!status.ok()) throw std::invalid_argument("CollisionScene: link " + status.message);
    impl_->link_names.push_back(link.link_name);
    impl_->links.push_back(std::move(body));
  }
  for (const auto& [a, b] : disabled_pairs) {
    for (const std::string& name : {a, b}) {
      if (!impl_->link_index.count(name)) {
        throw std::invalid_argument("CollisionScene: disabled collision pair (" + a + ", " + b +
                                    ") names unknown link '" + name + "'");
      }
    }
    impl_->acm.setEntry(a, b, true);
  }
  impl_->rebuild();
}

CollisionScene::~CollisionScene() = default;
CollisionScene::CollisionScene(const CollisionScene& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
CollisionScene& CollisionScene::operator=(const CollisionScene& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
CollisionScene::CollisionScene(CollisionScene&&) noexcept = default;
CollisionScene& CollisionScene::operator=(CollisionScene&&) noexcept = default;

std::size_t CollisionScene::numLinks() const { return impl_->links.size(); }
const std::vector<std::string>& CollisionScene::linkNames() const { return impl_->link_names; }
int CollisionScene::linkIndex(const std::string& link_name) const {
  auto it = impl_->link_index.find(link_name);
  return it == impl_->link_index.end() ? -1 : it->second;
}

const AllowedCollisionMatrix& CollisionScene::allowedCollisionMatrix() const { return impl_->acm; }

SceneStatus CollisionScene::setAllowed(const std::string& a, const std::string& b, bool allowed) {
  for (const std::string& name : {a, b}) {
    if (!impl_->knownName(name)) {
      return error(SceneStatusCode::kUnknownName, "allowed collision entry: unknown link or object '" + name + "'");
    }
  }
  impl_->acm.setEntry(a, b, allowed);
  impl_->rebuild();
  return SceneStatus();
}

SceneStatus CollisionScene::setDefaultAllowed(const std::string& name, bool allowed) {
  if (!impl_->knownName(name)) {
    return error(SceneStatusCode::kUnknownName, "allowed collision default: unknown link or object '" + name + "'");
  }
  impl_->acm.setDefaultEntry(name, allowed);
  impl_->rebuild();
  return SceneStatus();
}

SceneStatus CollisionScene::setAllowedCollisionMatrix(const AllowedCollisionMatrix& acm) {
  for (const std::string& name : acm.names()) {
    if (!impl_->knownName(name)) {
      return error(SceneStatusCode::kUnknownName, "allowed collision matrix: unknown link or object '" + name + "'");
    }
  }
  impl_->acm = acm;
  impl_->rebuild();
  return SceneStatus();
}

SceneStatus CollisionScene::setLinkPadding(const std::string& link_name, double padding) {
  const int index = linkIndex(link_name);
  const SceneStatus status = setLinkValue(index < 0 ? nullptr : &impl_->links[index], link_name, "padding",
                                          &Body::padding, padding, padding >= 0.0, ">= 0");
  if (status.ok()) impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::setPadding(double padding) {
  return setEveryLink(impl_->link_names, [&](const std::string& name) { return setLinkPadding(name, padding); });
}

SceneStatus CollisionScene::setLinkScale(const std::string& link_name, double scale) {
  const int index = linkIndex(link_name);
  const SceneStatus status = setLinkValue(index < 0 ? nullptr : &impl_->links[index], link_name, "scale",
                                          &Body::scale, scale, scale > 0.0, "> 0");
  if (status.ok()) impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::setScale(double scale) {
  return setEveryLink(impl_->link_names, [&](const std::string& name) { return setLinkScale(name, scale); });
}

double CollisionScene::linkPadding(const std::string& link_name) const {
  const int index = linkIndex(link_name);
  return index < 0 ? std::numeric_limits<double>::quiet_NaN() : impl_->links[index].padding;
}

double CollisionScene::linkScale(const std::string& link_name) const {
  const int index = linkIndex(link_name);
  return index < 0 ? std::numeric_limits<double>::quiet_NaN() : impl_->links[index].scale;
}

SceneStatus CollisionScene::addWorldObject(const WorldObject& object) {
  SceneStatus status = checkNewId("world object", object.id, impl_->knownName(object.id));
  if (!status.ok()) return status;
  status = appendBody(objectBody(object.id, BodyType::kWorldObject, object.pose, object.shapes), "world object",
                      &impl_->world);
  if (status.ok()) impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::moveWorldObject(const std::string& id, const Eigen::Isometry3d& pose) {
  const int w = Impl::findBody(impl_->world, id);
  const SceneStatus status = checkObjectMove(w, "move", "world object", id, "pose of", pose);
  if (!status.ok()) return status;
  impl_->world[w].pose = pose;
  impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::removeWorldObject(const std::string& id) {
  if (impl_->removeBody(&impl_->world, id)) return SceneStatus();
  return error(SceneStatusCode::kUnknownName, "remove: unknown world object '" + id + "'");
}

void CollisionScene::clearWorld() {
  for (const Body& body : impl_->world) impl_->acm.removeName(body.name);
  impl_->world.clear();
  impl_->rebuild();
}

std::vector<std::string> CollisionScene::worldObjectIds() const {
  std::vector<std::string> ids;
  for (const Body& body : impl_->world) ids.push_back(body.name);
  return ids;
}

bool CollisionScene::hasWorldObject(const std::string& id) const { return Impl::findBody(impl_->world, id) >= 0; }

SceneStatus CollisionScene::attachObject(const AttachedObject& object) {
  SceneStatus status = checkNewId("attached object", object.id, impl_->knownName(object.id));
  if (!status.ok()) return status;
  const int link = linkIndex(object.link_name);
  if (link < 0) {
    return error(SceneStatusCode::kUnknownName,
                 "attached object '" + object.id + "': unknown link '" + object.link_name + "'");
  }
  for (const std::string& touch : object.touch_links) {
    if (linkIndex(touch) < 0) {
      return error(SceneStatusCode::kUnknownName,
                   "attached object '" + object.id + "': unknown touch link '" + touch + "'");
    }
  }
  Body body = objectBody(object.id, BodyType::kAttachedObject, object.pose_in_link, object.shapes);
  body.link = link;
  body.touch_links = object.touch_links;
  status = appendBody(std::move(body), "attached object", &impl_->attached);
  if (status.ok()) impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::attachWorldObject(const std::string& id, const std::string& link_name,
                                              const Eigen::Isometry3d& link_pose,
                                              const std::vector<std::string>& touch_links) {
  const int w = Impl::findBody(impl_->world, id);
  SceneStatus status = checkObjectMove(w, "attach", "world object", id, "link pose for", link_pose);
  if (!status.ok()) return status;
  AttachedObject object;
  object.id = id;
  object.link_name = link_name;
  object.pose_in_link = link_pose.inverse() * impl_->world[w].pose;
  object.shapes = impl_->world[w].source;
  object.touch_links = touch_links;
  // Take it out of the world first (its id must be free), restoring it if attaching fails.
  Body saved = std::move(impl_->world[w]);
  impl_->world.erase(impl_->world.begin() + w);
  status = attachObject(object);
  if (!status.ok()) {
    impl_->world.insert(impl_->world.begin() + w, std::move(saved));
    impl_->rebuild();
  }
  return status;
}

SceneStatus CollisionScene::detachObject(const std::string& id, const Eigen::Isometry3d& link_pose) {
  const int a = Impl::findBody(impl_->attached, id);
  const SceneStatus status = checkObjectMove(a, "detach", "attached object", id, "link pose for", link_pose);
  if (!status.ok()) return status;
  Body body = std::move(impl_->attached[a]);
  impl_->attached.erase(impl_->attached.begin() + a);
  body.type = BodyType::kWorldObject;
  body.pose = link_pose * body.pose;
  body.link = -1;
  body.touch_links.clear();
  impl_->world.push_back(std::move(body));
  impl_->rebuild();
  return SceneStatus();
}

SceneStatus CollisionScene::removeAttachedObject(const std::string& id) {
  if (impl_->removeBody(&impl_->attached, id)) return SceneStatus();
  return error(SceneStatusCode::kUnknownName, "remove: unknown attached object '" + id + "'");
}

std::vector<std::string> CollisionScene::attachedObjectIds() const {
  std::vector<std::string> ids;
  for (const Body& body : impl_->attached) ids.push_back(body.name);
  return ids;
}

bool CollisionScene::hasAttachedObject(const std::string& id) const {
  return Impl::findBody(impl_->attached, id) >= 0;
}

void CollisionScene::setOccupancyMap(std::shared_ptr<const OccupancyMap> map, const Eigen::Isometry3d& map_pose) {
  impl_->setOccupancy(std::move(map), map_pose);
}

std::shared_ptr<const OccupancyMap> CollisionScene::occupancyMap() const { return impl_->occupancy; }

std::vector<PlacedShape> CollisionScene::bodyShapes(const std::vector<Eigen::Isometry3d>& link_poses) const {
  impl_->checkPoses(link_poses);
  std::vector<PlacedShape> shapes;
  for (int r = 0, n = impl_->robotCount(); r < n; ++r) {
    const Body& body = impl_->robot(r);
    const Eigen::Isometry3d base =
        body.type == BodyType::kAttachedObject ? link_poses[body.link] * body.pose : link_poses[body.link];
    for (const PlacedShape& placed : body.source) shapes.push_back(PlacedShape{placed.shape, base * placed.origin});
  }
  for (const Body& body : impl_->world) {
    for (const PlacedShape& placed : body.source) {
      shapes.push_back(PlacedShape{placed.shape, body.pose * placed.origin});
    }
  }
  return shapes;
}

bool CollisionScene::isColliding(const std::vector<Eigen::Isometry3d>& link_poses, CollisionScope scope) const {
  impl_->checkPoses(link_poses);
  // The hot path of planning: shape poses go to a per-thread buffer instead of a new vector per query.
  thread_local std::vector<ShapePose> poses;
  impl_->shapePoses(link_poses, &poses);
  const CollisionRequest request;
  Impl::Query q;
  q.scene = impl_.get();
  q.poses = &poses;
  q.request = &request;
  if (scope != CollisionScope::kWorld) impl_->selfCollision(&q);
  if (!q.done && scope != CollisionScope::kSelf) impl_->worldCollision(&q);
  return q.colliding;
}

CollisionReport CollisionScene::checkCollision(const std::vector<Eigen::Isometry3d>& link_poses,
                                               const CollisionRequest& request) const {
  impl_->checkPoses(link_poses);
  const std::vector<ShapePose> poses = impl_->shapePoses(link_poses);
  CollisionRequest effective = request;
  effective.max_contacts_per_pair = std::max<std::size_t>(1, request.max_contacts_per_pair);
  CollisionReport report;
  Impl::Query q;
  q.scene = impl_.get();
  q.poses = &poses;
  q.request = &effective;
  q.report = &report;
  if (request.scope != CollisionScope::kWorld) impl_->selfCollision(&q);
  if (!q.done && request.scope != CollisionScope::kSelf) impl_->worldCollision(&q);
  report.colliding = q.colliding;
  return report;
}

DistanceReport CollisionScene::distance(const std::vector<Eigen::Isometry3d>& link_poses,
                                        CollisionScope scope) const {
  impl_->checkPoses(link_poses);
  const Impl& s = *impl_;
  const std::vector<ShapePose> poses = s.shapePoses(link_poses);
  DistanceReport report;
  // Shape pairs whose bounding boxes are already farther apart than the best distance are skipped.
  if (scope != CollisionScope::kWorld) {
    for (const auto& [a, b] : s.self_pairs) {
      const Body& ba = s.robot(a);
      const Body& bb = s.robot(b);
      for (std::size_t i = 0; i < ba.shapes.size(); ++i) {
        const ShapePose& pa = poses[s.shape_offset[a] + i];
        for (std::size_t j = 0; j < bb.shapes.size(); ++j) {
          const ShapePose& pb = poses[s.shape_offset[b] + j];
          if (prunable(pa.aabb.distance(pb.aabb), report.distance)) continue;
          Impl::consider(&report, shapeDistance(ba.shapes[i], pa.tf, bb.shapes[j], pb.tf), ba, bb);
        }
      }
    }
  }
  if (scope != CollisionScope::kSelf) {
    for (int r = 0, n = s.robotCount(); r < n; ++r) {
      if (!s.robot_has_world_pair[r]) continue;
      const Body& rb = s.robot(r);
      for (std::size_t i = 0; i < rb.shapes.size(); ++i) {
        const ShapePose& pr = poses[s.shape_offset[r] + i];
        for (const auto& tag : s.world_tags) {
          if (!s.robot_world_checked[r * s.world.size() + tag->body]) continue;
          if (prunable(pr.aabb.distance(tag->aabb), report.distance)) continue;
          const Body& wb = s.world[tag->body];
          Impl::consider(&report, shapeDistance(rb.shapes[i], pr.tf, wb.shapes[tag->shape], tag->tf), rb, wb);
        }
      }
    }
  }
  return report;
}

}  // namespace sixdof_core
