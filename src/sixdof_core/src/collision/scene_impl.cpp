#include "scene_impl.h"

#include <algorithm>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>
#include <sstream>
#include <stdexcept>

#include "occupancy_map_impl.h"

namespace sixdof_core {

using detail::Body;
using detail::narrowPhase;
using detail::PairDistance;
using detail::ShapeInstance;
using detail::ShapePose;
using detail::worldAabb;
using detail::WorldShapeTag;

namespace {

// A contact or a distance report names its two bodies as the query found them.
void setBodies(const Body& b1, const Body& b2, BodyPair* pair) {
  pair->body1 = b1.name;
  pair->body2 = b2.name;
  pair->type1 = b1.type;
  pair->type2 = b2.type;
}

}  // namespace

bool CollisionScene::Impl::pairAllowed(const Body& a, const Body& b) const {
  if (a.type != BodyType::kWorldObject && b.type != BodyType::kWorldObject && a.link == b.link) return true;
  if (a.type == BodyType::kAttachedObject &&
      std::find(a.touch_links.begin(), a.touch_links.end(), b.name) != a.touch_links.end()) {
    return true;
  }
  if (b.type == BodyType::kAttachedObject &&
      std::find(b.touch_links.begin(), b.touch_links.end(), a.name) != b.touch_links.end()) {
    return true;
  }
  return acm.isAllowed(a.name, b.name);
}

void CollisionScene::Impl::rebuild() {
  const int n = robotCount();
  self_pairs.clear();
  shape_offset.assign(n, 0);
  robot_shape_count = 0;
  for (int r = 0; r < n; ++r) {
    shape_offset[r] = robot_shape_count;
    robot_shape_count += static_cast<int>(robot(r).shapes.size());
  }
  for (int a = 0; a < n; ++a) {
    if (robot(a).shapes.empty()) continue;
    for (int b = a + 1; b < n; ++b) {
      if (!robot(b).shapes.empty() && !pairAllowed(robot(a), robot(b))) self_pairs.emplace_back(a, b);
    }
  }
  robot_world_checked.assign(static_cast<std::size_t>(n) * world.size(), 0);
  robot_has_world_pair.assign(n, 0);
  for (int r = 0; r < n; ++r) {
    if (robot(r).shapes.empty()) continue;
    for (std::size_t w = 0; w < world.size(); ++w) {
      const bool checked = !pairAllowed(robot(r), world[w]);
      robot_world_checked[r * world.size() + w] = checked;
      robot_has_world_pair[r] |= checked;
    }
  }
  manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
  world_tags.clear();
  world_objects.clear();
  std::vector<fcl::CollisionObjectd*> objects;
  for (std::size_t w = 0; w < world.size(); ++w) {
    for (std::size_t s = 0; s < world[w].shapes.size(); ++s) {
      const ShapeInstance& shape = world[w].shapes[s];
      auto tag = std::make_unique<WorldShapeTag>();
      tag->body = static_cast<int>(w);
      tag->shape = static_cast<int>(s);
      tag->tf = world[w].pose * shape.origin;
      tag->aabb = worldAabb(*shape.geometry, tag->tf);
      tag->clearance = detail::clearanceShape(*shape.geometry, shape.obb, tag->tf);
      // The tree holds a private box proxy of the shape's world AABB: tight bounds for any rotation,
      // and FCL's CollisionObject never touches the (possibly shared, cached) real geometry.
      auto proxy = std::make_shared<fcl::Boxd>(tag->aabb.max_ - tag->aabb.min_);
      auto object = std::make_unique<fcl::CollisionObjectd>(proxy, Eigen::Isometry3d(Eigen::Translation3d(
                                                                        tag->aabb.center())));
      object->setUserData(tag.get());
      objects.push_back(object.get());
      world_tags.push_back(std::move(tag));
      world_objects.push_back(std::move(object));
    }
  }
  manager->registerObjects(objects);
  manager->setup();
  // The pre-check's spheres of each robot body, gathered into its link's frame.
  sphere_trees.assign(n, {});
  for (int r = 0; r < n; ++r) {
    const Body& body = robot(r);
    const Eigen::Isometry3d base =
        body.type == BodyType::kAttachedObject ? body.pose : Eigen::Isometry3d(Eigen::Isometry3d::Identity());
    std::vector<detail::Sphere> spheres;
    for (const ShapeInstance& shape : body.shapes) {
      const Eigen::Isometry3d tf = base * shape.origin;
      for (const detail::Sphere& s : shape.spheres) spheres.push_back(detail::Sphere{tf * s.center, s.radius});
    }
    sphere_trees[r] = detail::buildSphereTree(std::move(spheres));
  }
}

void CollisionScene::Impl::checkPoses(const std::vector<Eigen::Isometry3d>& poses) const {
  if (poses.size() != links.size()) {
    std::ostringstream msg;
    msg << "CollisionScene: got " << poses.size() << " link poses for " << links.size() << " links";
    throw std::invalid_argument(msg.str());
  }
}

void CollisionScene::Impl::shapePoses(const std::vector<Eigen::Isometry3d>& poses, std::vector<ShapePose>* out) const {
  out->resize(robot_shape_count);
  for (int r = 0, n = robotCount(); r < n; ++r) {
    const Body& body = robot(r);
    if (body.shapes.empty()) continue;
    const Eigen::Isometry3d base = body.type == BodyType::kAttachedObject ? poses[body.link] * body.pose
                                                                          : poses[body.link];
    for (std::size_t s = 0; s < body.shapes.size(); ++s) {
      const ShapeInstance& shape = body.shapes[s];
      ShapePose& sp = (*out)[shape_offset[r] + s];
      sp.tf = shape.origin_is_identity ? base : base * shape.origin;
      sp.aabb = worldAabb(*shape.geometry, sp.tf);
    }
  }
}

void CollisionScene::Impl::record(Query* q, const Body& b1, const Body& b2, const std::vector<fcl::Contactd>& contacts,
                                  std::size_t* pair_count) {
  for (const auto& c : contacts) {
    if (*pair_count >= q->request->max_contacts_per_pair) break;
    Contact out;
    setBodies(b1, b2, &out);
    out.position = c.pos;
    out.normal = c.normal;
    out.depth = c.penetration_depth;
    q->report->contacts.push_back(out);
    ++*pair_count;
  }
}

void CollisionScene::Impl::finishPair(Query* q) const {
  q->colliding = true;
  ++q->pairs;
  if (!q->report || (q->request->max_pairs > 0 && q->pairs >= q->request->max_pairs)) q->done = true;
}

void CollisionScene::Impl::selfCollision(Query* q) const {
  const auto& sp = *q->poses;
  std::vector<fcl::Contactd> contacts;
  for (const auto& [a, b] : self_pairs) {
    const Body& ba = robot(a);
    const Body& bb = robot(b);
    bool hit = false;
    std::size_t pair_count = 0;
    for (std::size_t i = 0; i < ba.shapes.size() && !(hit && !q->report); ++i) {
      const ShapePose& pa = sp[shape_offset[a] + i];
      for (std::size_t j = 0; j < bb.shapes.size(); ++j) {
        const ShapePose& pb = sp[shape_offset[b] + j];
        if (!pa.aabb.overlap(pb.aabb)) continue;
        contacts.clear();
        if (!narrowPhase(ba.shapes[i], pa.tf, bb.shapes[j], pb.tf, q->request->max_contacts_per_pair,
                         q->report ? &contacts : nullptr)) {
          continue;
        }
        hit = true;
        if (!q->report) break;
        record(q, ba, bb, contacts, &pair_count);
      }
    }
    if (hit) {
      finishPair(q);
      if (q->done) return;
    }
  }
}

bool CollisionScene::Impl::worldPair(Query* q, int r, int s, const WorldShapeTag& tag) const {
  if (!robot_world_checked[r * world.size() + tag.body]) return false;
  const ShapePose& pose = (*q->poses)[shape_offset[r] + s];
  if (!pose.aabb.overlap(tag.aabb)) return false;
  const Body& rb = robot(r);
  const Body& wb = world[tag.body];
  std::vector<fcl::Contactd> contacts;
  if (!narrowPhase(rb.shapes[s], pose.tf, wb.shapes[tag.shape], tag.tf, q->request->max_contacts_per_pair,
                   q->report ? &contacts : nullptr)) {
    return false;
  }
  if (!q->report) {
    finishPair(q);
    return true;
  }
  auto [it, first] = q->world_pair_contacts.emplace(std::make_pair(r, tag.body), 0);
  record(q, rb, wb, contacts, &it->second);
  if (first) finishPair(q);
  return q->done;
}

bool CollisionScene::Impl::visitWorld(Query* q, int r, int s, const fcl::detail::NodeBase<fcl::AABBd>* node) const {
  if (node == nullptr || !node->bv.overlap((*q->poses)[shape_offset[r] + s].aabb)) return false;
  if (node->isLeaf()) {
    const auto* object = static_cast<const fcl::CollisionObjectd*>(node->data);
    return worldPair(q, r, s, *static_cast<const WorldShapeTag*>(object->getUserData()));
  }
  return visitWorld(q, r, s, node->children[0]) || visitWorld(q, r, s, node->children[1]);
}

void CollisionScene::Impl::worldCollision(Query* q) const {
  if (!world.empty()) {
    const auto* root = manager->getTree().getRoot();
    for (int r = 0, n = robotCount(); r < n && !q->done; ++r) {
      if (!robot_has_world_pair[r]) continue;
      for (std::size_t s = 0; s < robot(r).shapes.size() && !q->done; ++s) {
        visitWorld(q, r, static_cast<int>(s), root);
      }
    }
  }
  if (!q->done && octree) octreeCollision(q);
}

void CollisionScene::Impl::setOccupancy(std::shared_ptr<const OccupancyMap> map, const Eigen::Isometry3d& pose) {
  occupancy = std::move(map);
  occupancy_pose = pose;
  octree.reset();
  Eigen::Vector3d lo, hi;
  if (!occupancy || !occupancy->occupiedBounds(&lo, &hi)) return;
  octree = std::make_shared<const fcl::OcTreed>(detail::OccupancyMapAccess::tree(*occupancy));
  // The octree's own bounding volume is the whole key space; the occupied cells' box prunes far better.
  const Eigen::Vector3d center = pose * (0.5 * (lo + hi));
  const Eigen::Vector3d extent = pose.linear().cwiseAbs() * (0.5 * (hi - lo));
  octree_aabb = fcl::AABBd(center - extent, center + extent);
  octree_box = detail::clearanceBox(octree_aabb.min_, octree_aabb.max_);
}

void CollisionScene::Impl::octreeCollision(Query* q) const {
  const std::size_t max_contacts = q->report ? q->request->max_contacts_per_pair : 1;
  const fcl::CollisionRequestd request(max_contacts, q->report != nullptr);
  std::vector<fcl::Contactd> contacts;
  for (int r = 0, n = robotCount(); r < n; ++r) {
    const Body& body = robot(r);
    bool hit = false;
    std::size_t pair_count = 0;
    for (std::size_t s = 0; s < body.shapes.size(); ++s) {
      const ShapePose& pose = (*q->poses)[shape_offset[r] + s];
      if (!pose.aabb.overlap(octree_aabb)) continue;
      fcl::CollisionResultd result;
      fcl::collide(body.shapes[s].geometry.get(), pose.tf, octree.get(), occupancy_pose, request, result);
      if (!result.isCollision()) continue;
      hit = true;
      if (!q->report) break;
      contacts.clear();
      result.getContacts(contacts);
      record(q, body, octomap_body, contacts, &pair_count);
    }
    if (hit) {
      finishPair(q);
      if (q->done) return;
    }
  }
}

void CollisionScene::Impl::consider(DistanceReport* report, const PairDistance& d, const Body& b1, const Body& b2) {
  if (d.distance >= report->distance) return;
  report->found = true;
  report->distance = d.distance;
  setBodies(b1, b2, report);
  report->point1 = d.p1;
  report->point2 = d.p2;
}

}  // namespace sixdof_core
