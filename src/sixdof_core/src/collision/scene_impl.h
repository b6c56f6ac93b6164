#pragma once

// The collision scene's private state and queries: the bodies, the pairs to check (derived by rebuild()),
// the world's broad phase and the self/world collision walks. Only the collision sources include this.

#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/contact.h>

#include "fcl_geometry.h"
#include "narrow_phase.h"
#include "sixdof_core/collision.h"
#include "sixdof_core/occupancy_map.h"

namespace sixdof_core {
namespace detail {

struct Body {
  std::string name;
  BodyType type = BodyType::kRobotLink;
  int link = -1;                                        // link the body moves with (links, attached objects)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // attached: in the link; world: in the world
  std::vector<PlacedShape> source;
  std::vector<ShapeInstance> shapes;
  std::vector<std::string> touch_links;
  double padding = 0.0;  // links only
  double scale = 1.0;    // links only
};

// A world shape as registered in the broad phase; the manager hands it back through the user data.
struct WorldShapeTag {
  int body = 0;
  int shape = 0;
  Eigen::Isometry3d tf;
  fcl::AABBd aabb;
  ClearanceShape clearance;  // what the pre-check measures
};

struct ShapePose {
  Eigen::Isometry3d tf;
  fcl::AABBd aabb;
};

}  // namespace detail

struct CollisionScene::Impl {
  std::vector<detail::Body> links;
  std::vector<detail::Body> attached;
  std::vector<detail::Body> world;
  std::vector<std::string> link_names;
  std::unordered_map<std::string, int> link_index;
  AllowedCollisionMatrix acm;

  // Derived from the above by rebuild(); queries read only these.
  std::vector<std::pair<int, int>> self_pairs;  // robot body indices (links, then attached objects)
  std::vector<char> robot_world_checked;        // [robot body * world.size() + world body]
  std::vector<char> robot_has_world_pair;       // per robot body
  std::vector<int> shape_offset;                // per robot body, into the per-query shape poses
  int robot_shape_count = 0;
  std::vector<std::unique_ptr<detail::WorldShapeTag>> world_tags;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> world_objects;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager;
  std::vector<std::vector<detail::SphereNode>> sphere_trees;  // per robot body, in its link's frame (pre-check)

  // The occupancy map and FCL's octree geometry over its tree; octree is null while the map has no occupied cell.
  std::shared_ptr<const OccupancyMap> occupancy;
  Eigen::Isometry3d occupancy_pose = Eigen::Isometry3d::Identity();
  std::shared_ptr<const fcl::OcTreed> octree;
  fcl::AABBd octree_aabb;  // world frame, around the occupied cells
  detail::ClearanceShape octree_box;  // the same box, for the pre-check
  detail::Body octomap_body;

  Impl() { octomap_body.name = kOccupancyMapBody; octomap_body.type = BodyType::kWorldObject; }
  Impl(const Impl& o) : Impl() {
    links = o.links;
    attached = o.attached;
    world = o.world;
    link_names = o.link_names;
    link_index = o.link_index;
    acm = o.acm;
    occupancy = o.occupancy;
    occupancy_pose = o.occupancy_pose;
    octree = o.octree;
    octree_aabb = o.octree_aabb;
    octree_box = o.octree_box;
    rebuild();
  }

  void setOccupancy(std::shared_ptr<const OccupancyMap> map, const Eigen::Isometry3d& pose);

  int robotCount() const { return static_cast<int>(links.size() + attached.size()); }
  const detail::Body& robot(int r) const {
    return r < static_cast<int>(links.size()) ? links[r] : attached[r - links.size()];
  }

  bool knownName(const std::string& name) const {
    return link_index.count(name) > 0 || findBody(attached, name) >= 0 || findBody(world, name) >= 0;
  }

  static int findBody(const std::vector<detail::Body>& bodies, const std::string& name) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }

  // Removes the object `id` from `bodies` (world or attached) and from the allowed collision matrix; false when
  // there is none.
  bool removeBody(std::vector<detail::Body>* bodies, const std::string& id) {
    const int index = findBody(*bodies, id);
    if (index < 0) return false;
    bodies->erase(bodies->begin() + index);
    acm.removeName(id);
    rebuild();
    return true;
  }

  bool pairAllowed(const detail::Body& a, const detail::Body& b) const;

  void rebuild();

  void checkPoses(const std::vector<Eigen::Isometry3d>& poses) const;

  std::vector<detail::ShapePose> shapePoses(const std::vector<Eigen::Isometry3d>& poses) const {
    std::vector<detail::ShapePose> out;
    shapePoses(poses, &out);
    return out;
  }

  void shapePoses(const std::vector<Eigen::Isometry3d>& poses, std::vector<detail::ShapePose>* out) const;

  // Shared by the boolean and the reporting query. With a report, contacts are gathered per body pair.
  struct Query {
    const Impl* scene = nullptr;
    const std::vector<detail::ShapePose>* poses = nullptr;
    const CollisionRequest* request = nullptr;
    CollisionReport* report = nullptr;  // null: boolean fast path
    bool colliding = false;
    bool done = false;
    std::size_t pairs = 0;
    std::map<std::pair<int, int>, std::size_t> world_pair_contacts;
  };

  static void record(Query* q, const detail::Body& b1, const detail::Body& b2,
                     const std::vector<fcl::Contactd>& contacts, std::size_t* pair_count);

  void finishPair(Query* q) const;

  void selfCollision(Query* q) const;

  // Robot shape r/s against the world shape of `tag` (broad phase already passed).
  bool worldPair(Query* q, int r, int s, const detail::WorldShapeTag& tag) const;

  // Walks the world's AABB tree read-only (the manager's own query API would build a temporary
  // fcl::CollisionObject, which recomputes the shared geometry's local AABB: a write on every query).
  bool visitWorld(Query* q, int r, int s, const fcl::detail::NodeBase<fcl::AABBd>* node) const;

  void worldCollision(Query* q) const;

  // Robot bodies against the occupancy map's occupied cells.
  void octreeCollision(Query* q) const;

  // CollisionScene::precheckMotion (precheck.cpp, where the Certifier walks the sphere trees).
  class Certifier;
  SphereCertificate certifyMotion(const std::vector<Eigen::Isometry3d>& poses, const LinkMotionBound& bound, double cap,
                                  double tolerance) const;

  static void consider(DistanceReport* report, const detail::PairDistance& d, const detail::Body& b1,
                       const detail::Body& b2);
};

}  // namespace sixdof_core
