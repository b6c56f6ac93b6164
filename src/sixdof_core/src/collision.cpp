#include "sixdof_core/collision.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <fcl/fcl.h>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "sixdof_core/mesh_loader.h"

namespace sixdof_core {
namespace {

using GeometryPtr = std::shared_ptr<fcl::CollisionGeometryd>;

// Oriented bounding box of a shape in the shape's own frame: a cheap, conservative separation test that
// runs before FCL's narrow phase. Link hulls are long and sit diagonally in the world, so their world AABBs
// overlap far more often than the shapes themselves (measured: 99.5 % of the pairs that reached FCL in the
// planning benchmark did not collide).
struct Obb {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: unit axes
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

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

// Separating-axis test of two oriented boxes placed by tf1 and tf2 (the 15 axes of Gottschalk et al.); a
// small tolerance keeps it conservative under rounding. False means the boxes are certainly disjoint.
bool obbOverlap(const Obb& a, const Eigen::Isometry3d& tf1, const Obb& b, const Eigen::Isometry3d& tf2) {
  constexpr double kEps = 1e-9;
  const Eigen::Matrix3d ra = tf1.linear() * a.axes;
  const Eigen::Matrix3d rb = tf2.linear() * b.axes;
  const Eigen::Matrix3d r = ra.transpose() * rb;  // b's axes in a's frame
  const Eigen::Vector3d t = ra.transpose() * ((tf2 * b.center) - (tf1 * a.center));
  const Eigen::Matrix3d abs_r = r.cwiseAbs().array() + kEps;
  const Eigen::Vector3d& ea = a.half;
  const Eigen::Vector3d& eb = b.half;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > ea[i] + abs_r.row(i).dot(eb)) return false;
  }
  for (int j = 0; j < 3; ++j) {
    if (std::abs(t.dot(r.col(j))) > ea.dot(abs_r.col(j)) + eb[j]) return false;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra_ij = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const double rb_ij = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      if (std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) > ra_ij + rb_ij) return false;
    }
  }
  return true;
}

struct ShapeInstance {
  GeometryPtr geometry;
  Eigen::Isometry3d origin;  // in the body's frame
  Obb obb;                   // in the shape's frame (geometry coordinates)
  bool origin_is_identity = false;
};

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
};

struct ShapePose {
  Eigen::Isometry3d tf;
  fcl::AABBd aabb;
};

fcl::AABBd worldAabb(const fcl::CollisionGeometryd& geometry, const Eigen::Isometry3d& tf) {
  const fcl::AABBd& local = geometry.aabb_local;
  const Eigen::Vector3d center = tf * local.center();
  const Eigen::Vector3d extent = tf.linear().cwiseAbs() * ((local.max_ - local.min_) * 0.5);
  return fcl::AABBd(center - extent, center + extent);
}

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

SceneStatus error(SceneStatusCode code, const std::string& message) { return SceneStatus{code, message}; }

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
      if (!loaded.ok) {
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

SceneStatus buildShapes(Body* body) {
  body->shapes.clear();
  for (const PlacedShape& placed : body->source) {
    SceneStatus status;
    GeometryPtr geometry = makeGeometry(placed.shape, body->scale, body->padding, &status);
    if (!geometry) {
      status.message = "'" + body->name + "': " + describe(placed.shape) + ": " + status.message;
      return status;
    }
    body->shapes.push_back(ShapeInstance{geometry, placed.origin, geometryObb(*geometry),
                                         placed.origin.matrix().isIdentity(0.0)});
  }
  return SceneStatus();
}

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

struct PairDistance {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d p2 = Eigen::Vector3d::Zero();
};

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

// Boxes farther apart than the best distance cannot improve it; while the best is a penetration, only
// overlapping boxes can hold a deeper one.
bool prunable(double box_distance, double best) { return best <= 0.0 ? box_distance > 0.0 : box_distance >= best; }

}  // namespace

struct CollisionScene::Impl {
  std::vector<Body> links;
  std::vector<Body> attached;
  std::vector<Body> world;
  std::vector<std::string> link_names;
  std::unordered_map<std::string, int> link_index;
  AllowedCollisionMatrix acm;

  // Derived from the above by rebuild(); queries read only these.
  std::vector<std::pair<int, int>> self_pairs;  // robot body indices (links, then attached objects)
  std::vector<char> robot_world_checked;        // [robot body * world.size() + world body]
  std::vector<char> robot_has_world_pair;       // per robot body
  std::vector<int> shape_offset;                // per robot body, into the per-query shape poses
  int robot_shape_count = 0;
  std::vector<std::unique_ptr<WorldShapeTag>> world_tags;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> world_objects;
  std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd> manager;

  Impl() = default;
  Impl(const Impl& o) : links(o.links), attached(o.attached), world(o.world), link_names(o.link_names),
                        link_index(o.link_index), acm(o.acm) {
    rebuild();
  }

  int robotCount() const { return static_cast<int>(links.size() + attached.size()); }
  const Body& robot(int r) const {
    return r < static_cast<int>(links.size()) ? links[r] : attached[r - links.size()];
  }

  bool knownName(const std::string& name) const {
    return link_index.count(name) > 0 || findBody(attached, name) >= 0 || findBody(world, name) >= 0;
  }

  static int findBody(const std::vector<Body>& bodies, const std::string& name) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }

  bool pairAllowed(const Body& a, const Body& b) const {
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

  void rebuild() {
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
  }

  void checkPoses(const std::vector<Eigen::Isometry3d>& poses) const {
    if (poses.size() != links.size()) {
      std::ostringstream msg;
      msg << "CollisionScene: got " << poses.size() << " link poses for " << links.size() << " links";
      throw std::invalid_argument(msg.str());
    }
  }

  std::vector<ShapePose> shapePoses(const std::vector<Eigen::Isometry3d>& poses) const {
    std::vector<ShapePose> out;
    shapePoses(poses, &out);
    return out;
  }

  void shapePoses(const std::vector<Eigen::Isometry3d>& poses, std::vector<ShapePose>* out) const {
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

  // Shared by the boolean and the reporting query. With a report, contacts are gathered per body pair.
  struct Query {
    const Impl* scene = nullptr;
    const std::vector<ShapePose>* poses = nullptr;
    const CollisionRequest* request = nullptr;
    CollisionReport* report = nullptr;  // null: boolean fast path
    bool colliding = false;
    bool done = false;
    std::size_t pairs = 0;
    std::map<std::pair<int, int>, std::size_t> world_pair_contacts;
  };

  static void record(Query* q, const Body& b1, const Body& b2, const std::vector<fcl::Contactd>& contacts,
                     std::size_t* pair_count) {
    for (const auto& c : contacts) {
      if (*pair_count >= q->request->max_contacts_per_pair) break;
      Contact out;
      out.body1 = b1.name;
      out.body2 = b2.name;
      out.type1 = b1.type;
      out.type2 = b2.type;
      out.position = c.pos;
      out.normal = c.normal;
      out.depth = c.penetration_depth;
      q->report->contacts.push_back(out);
      ++*pair_count;
    }
  }

  void finishPair(Query* q) const {
    q->colliding = true;
    ++q->pairs;
    if (!q->report || (q->request->max_pairs > 0 && q->pairs >= q->request->max_pairs)) q->done = true;
  }

  void selfCollision(Query* q) const {
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

  // Robot shape r/s against the world shape of `tag` (broad phase already passed).
  bool worldPair(Query* q, int r, int s, const WorldShapeTag& tag) const {
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

  // Walks the world's AABB tree read-only (the manager's own query API would build a temporary
  // fcl::CollisionObject, which recomputes the shared geometry's local AABB: a write on every query).
  bool visitWorld(Query* q, int r, int s, const fcl::detail::NodeBase<fcl::AABBd>* node) const {
    if (node == nullptr || !node->bv.overlap((*q->poses)[shape_offset[r] + s].aabb)) return false;
    if (node->isLeaf()) {
      const auto* object = static_cast<const fcl::CollisionObjectd*>(node->data);
      return worldPair(q, r, s, *static_cast<const WorldShapeTag*>(object->getUserData()));
    }
    return visitWorld(q, r, s, node->children[0]) || visitWorld(q, r, s, node->children[1]);
  }

  void worldCollision(Query* q) const {
    if (world.empty()) return;
    const auto* root = manager->getTree().getRoot();
    for (int r = 0, n = robotCount(); r < n && !q->done; ++r) {
      if (!robot_has_world_pair[r]) continue;
      for (std::size_t s = 0; s < robot(r).shapes.size() && !q->done; ++s) visitWorld(q, r, static_cast<int>(s), root);
    }
  }

  static void consider(DistanceReport* report, const PairDistance& d, const Body& b1, const Body& b2) {
    if (d.distance >= report->distance) return;
    report->found = true;
    report->distance = d.distance;
    report->body1 = b1.name;
    report->body2 = b2.name;
    report->type1 = b1.type;
    report->type2 = b2.type;
    report->point1 = d.p1;
    report->point2 = d.p2;
  }
};

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
  if (index < 0) return error(SceneStatusCode::kUnknownName, "padding: unknown link '" + link_name + "'");
  if (!std::isfinite(padding) || padding < 0.0) {
    return error(SceneStatusCode::kInvalidValue, "padding of '" + link_name + "' must be finite and >= 0");
  }
  Body& body = impl_->links[index];
  const double old = body.padding;
  body.padding = padding;
  SceneStatus status = buildShapes(&body);
  if (!status.ok()) {
    body.padding = old;
    buildShapes(&body);
    return status;
  }
  impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::setPadding(double padding) {
  for (const std::string& name : impl_->link_names) {
    SceneStatus status = setLinkPadding(name, padding);
    if (!status.ok()) return status;
  }
  return SceneStatus();
}

SceneStatus CollisionScene::setLinkScale(const std::string& link_name, double scale) {
  const int index = linkIndex(link_name);
  if (index < 0) return error(SceneStatusCode::kUnknownName, "scale: unknown link '" + link_name + "'");
  if (!std::isfinite(scale) || scale <= 0.0) {
    return error(SceneStatusCode::kInvalidValue, "scale of '" + link_name + "' must be finite and > 0");
  }
  Body& body = impl_->links[index];
  const double old = body.scale;
  body.scale = scale;
  SceneStatus status = buildShapes(&body);
  if (!status.ok()) {
    body.scale = old;
    buildShapes(&body);
    return status;
  }
  impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::setScale(double scale) {
  for (const std::string& name : impl_->link_names) {
    SceneStatus status = setLinkScale(name, scale);
    if (!status.ok()) return status;
  }
  return SceneStatus();
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
  if (object.id.empty()) return error(SceneStatusCode::kInvalidValue, "world object: empty id");
  if (impl_->knownName(object.id)) {
    return error(SceneStatusCode::kDuplicateName, "world object '" + object.id + "': name already in use");
  }
  if (object.shapes.empty()) {
    return error(SceneStatusCode::kInvalidShape, "world object '" + object.id + "': has no shapes");
  }
  if (!object.pose.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, "world object '" + object.id + "': pose is not finite");
  }
  Body body;
  body.name = object.id;
  body.type = BodyType::kWorldObject;
  body.pose = object.pose;
  body.source = object.shapes;
  SceneStatus status = buildShapes(&body);
  if (!status.ok()) {
    status.message = "world object " + status.message;
    return status;
  }
  impl_->world.push_back(std::move(body));
  impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::moveWorldObject(const std::string& id, const Eigen::Isometry3d& pose) {
  const int w = Impl::findBody(impl_->world, id);
  if (w < 0) return error(SceneStatusCode::kUnknownName, "move: unknown world object '" + id + "'");
  if (!pose.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, "move: pose of '" + id + "' is not finite");
  }
  impl_->world[w].pose = pose;
  impl_->rebuild();
  return SceneStatus();
}

SceneStatus CollisionScene::removeWorldObject(const std::string& id) {
  const int w = Impl::findBody(impl_->world, id);
  if (w < 0) return error(SceneStatusCode::kUnknownName, "remove: unknown world object '" + id + "'");
  impl_->world.erase(impl_->world.begin() + w);
  impl_->acm.removeName(id);
  impl_->rebuild();
  return SceneStatus();
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
  if (object.id.empty()) return error(SceneStatusCode::kInvalidValue, "attached object: empty id");
  if (impl_->knownName(object.id)) {
    return error(SceneStatusCode::kDuplicateName, "attached object '" + object.id + "': name already in use");
  }
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
  if (object.shapes.empty()) {
    return error(SceneStatusCode::kInvalidShape, "attached object '" + object.id + "': has no shapes");
  }
  if (!object.pose_in_link.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, "attached object '" + object.id + "': pose is not finite");
  }
  Body body;
  body.name = object.id;
  body.type = BodyType::kAttachedObject;
  body.link = link;
  body.pose = object.pose_in_link;
  body.source = object.shapes;
  body.touch_links = object.touch_links;
  SceneStatus status = buildShapes(&body);
  if (!status.ok()) {
    status.message = "attached object " + status.message;
    return status;
  }
  impl_->attached.push_back(std::move(body));
  impl_->rebuild();
  return status;
}

SceneStatus CollisionScene::attachWorldObject(const std::string& id, const std::string& link_name,
                                              const Eigen::Isometry3d& link_pose,
                                              const std::vector<std::string>& touch_links) {
  const int w = Impl::findBody(impl_->world, id);
  if (w < 0) return error(SceneStatusCode::kUnknownName, "attach: unknown world object '" + id + "'");
  if (!link_pose.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, "attach: link pose for '" + id + "' is not finite");
  }
  AttachedObject object;
  object.id = id;
  object.link_name = link_name;
  object.pose_in_link = link_pose.inverse() * impl_->world[w].pose;
  object.shapes = impl_->world[w].source;
  object.touch_links = touch_links;
  // Take it out of the world first (its id must be free), restoring it if attaching fails.
  Body saved = std::move(impl_->world[w]);
  impl_->world.erase(impl_->world.begin() + w);
  SceneStatus status = attachObject(object);
  if (!status.ok()) {
    impl_->world.insert(impl_->world.begin() + w, std::move(saved));
    impl_->rebuild();
  }
  return status;
}

SceneStatus CollisionScene::detachObject(const std::string& id, const Eigen::Isometry3d& link_pose) {
  const int a = Impl::findBody(impl_->attached, id);
  if (a < 0) return error(SceneStatusCode::kUnknownName, "detach: unknown attached object '" + id + "'");
  if (!link_pose.matrix().allFinite()) {
    return error(SceneStatusCode::kInvalidValue, "detach: link pose for '" + id + "' is not finite");
  }
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
  const int a = Impl::findBody(impl_->attached, id);
  if (a < 0) return error(SceneStatusCode::kUnknownName, "remove: unknown attached object '" + id + "'");
  impl_->attached.erase(impl_->attached.begin() + a);
  impl_->acm.removeName(id);
  impl_->rebuild();
  return SceneStatus();
}

std::vector<std::string> CollisionScene::attachedObjectIds() const {
  std::vector<std::string> ids;
  for (const Body& body : impl_->attached) ids.push_back(body.name);
  return ids;
}

bool CollisionScene::hasAttachedObject(const std::string& id) const {
  return Impl::findBody(impl_->attached, id) >= 0;
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
