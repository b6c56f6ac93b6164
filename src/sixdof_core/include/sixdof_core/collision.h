#pragma once

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/collision_matrix.h"
#include "sixdof_core/geometry.h"
#include "sixdof_core/result.h"

namespace sixdof_core {

enum class BodyType { kRobotLink, kAttachedObject, kWorldObject };

class OccupancyMap;

// The body name of the occupancy map's cells in contacts (MoveIt's OCTOMAP_NS); its type is kWorldObject.
inline constexpr char kOccupancyMapBody[] = "<octomap>";

// A planning-scene object fixed in the world: one id, one pose, several shapes placed in the object's frame.
struct WorldObject {
  std::string id;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::vector<PlacedShape> shapes;
};

// An object held by a link: it moves with the link and may touch the link and its touch_links
// (e.g. the fingers) without counting as a collision.
struct AttachedObject {
  std::string id;
  std::string link_name;
  Eigen::Isometry3d pose_in_link = Eigen::Isometry3d::Identity();
  std::vector<PlacedShape> shapes;
  std::vector<std::string> touch_links;
};

enum class SceneStatusCode { kOk, kUnknownName, kDuplicateName, kInvalidShape, kMeshLoadFailed, kInvalidValue };

using SceneStatus = Result<SceneStatusCode>;

enum class CollisionScope {
  kAll,    // self collision and robot vs world
  kSelf,   // robot links and attached objects among themselves
  kWorld,  // robot links and attached objects vs world objects
};

struct CollisionRequest {
  CollisionScope scope = CollisionScope::kAll;
  std::size_t max_contacts_per_pair = 1;
  // Stop after this many colliding body pairs (0: report every colliding pair).
  std::size_t max_pairs = 0;
};

// The two bodies a contact or a distance is between (links, attached or world objects).
struct BodyPair {
  std::string body1;
  std::string body2;
  BodyType type1 = BodyType::kRobotLink;
  BodyType type2 = BodyType::kRobotLink;
};

// One contact between two bodies. The normal points from body1 towards body2. With a non-convex mesh
// involved, FCL reports triangle-level contacts whose depth is only indicative.
struct Contact : BodyPair {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double depth = 0.0;
};

struct CollisionReport {
  bool colliding = false;
  std::vector<Contact> contacts;
};

// Signed minimum distance over the pairs in scope: negative = the deepest penetration among colliding
// pairs. point1/point2 are the closest points (world frame) on body1/body2; for a penetrating pair
// both are the deepest contact point.
struct DistanceReport : BodyPair {
  bool found = false;  // false when no pair is in scope (e.g. an empty world)
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector3d point1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d point2 = Eigen::Vector3d::Zero();
};

// How far the robot's links may move during a motion, per link as a sum of terms, one per joint that moves it. Over
// a fraction w of the motion (either way), a term moves every point p of the link (p in the link's frame, |p| its
// distance from the frame's origin) at most (linear + angular * |p|) * w + growth * w^2 / 2: the link turns at
// `angular` while its origin moves at `linear`, a speed that may grow by `growth` per unit of w. Two links with a
// term of the same `joint` (any id the caller chooses) move together under it, as under a joint above both in the
// kinematic tree: it does not change the distance between them.
struct LinkMotionBound {
  struct Term {
    int joint = 0;
    double linear = 0.0;   // m, >= 0
    double angular = 0.0;  // rad, >= 0
    double growth = 0.0;   // m, >= 0
  };
  std::vector<std::vector<Term>> links;  // per link, in the scene's link order
};

// What CollisionScene::precheckMotion proves: every state within `proven` (a fraction of the motion, either way)
// is collision-free; proven = 0: not even the first state is (isColliding decides). Then spheres overlap there, and
// they keep overlapping within `unprovable` of it: asking again there proves nothing either.
struct SphereCertificate {
  double proven = 0.0;
  double unprovable = 0.0;
};

struct CollisionSceneOptions {
  // Robot links grow by padding (m) after scaling by scale about each shape's origin, as in MoveIt.
  // Attached and world objects are neither padded nor scaled.
  double link_padding = 0.0;
  double link_scale = 1.0;
};

// Robot-vs-robot and robot-vs-world collision checking on FCL (double precision).
// Meshes: a convex mesh becomes an fcl::Convex (a solid, with penetration depths); any other mesh an
// OBBRSS BVH, which is a surface as in MoveIt: a body entirely inside it does not touch it.
// Link poses are passed per query (world frame = base_link), in the order of the LinkGeometry list given
// at construction, so the scene depends on no robot-model class. Queries are const and keep no per-call
// state: one scene can serve several threads while nobody modifies it.
class CollisionScene {
 public:
  // Throws std::invalid_argument on a duplicate or empty link name, an invalid shape, an unreadable mesh,
  // a disabled pair that names an unknown link, or invalid options.
  CollisionScene(const std::vector<LinkGeometry>& links,
                 const std::vector<std::pair<std::string, std::string>>& disabled_pairs,
                 const CollisionSceneOptions& options = CollisionSceneOptions());
  ~CollisionScene();
  CollisionScene(const CollisionScene& other);
  CollisionScene& operator=(const CollisionScene& other);
  CollisionScene(CollisionScene&&) noexcept;
  CollisionScene& operator=(CollisionScene&&) noexcept;

  std::size_t numLinks() const;
  const std::vector<std::string>& linkNames() const;
  int linkIndex(const std::string& link_name) const;  // -1 if unknown

  // Allowed collision matrix. Names must be robot links or current objects (kUnknownName otherwise).
  const AllowedCollisionMatrix& allowedCollisionMatrix() const;
  SceneStatus setAllowed(const std::string& a, const std::string& b, bool allowed);
  SceneStatus setDefaultAllowed(const std::string& name, bool allowed);
  SceneStatus setAllowedCollisionMatrix(const AllowedCollisionMatrix& acm);

  // Padding (m, >= 0) and scale (> 0) of robot links.
  SceneStatus setLinkPadding(const std::string& link_name, double padding);
  SceneStatus setPadding(double padding);
  SceneStatus setLinkScale(const std::string& link_name, double scale);
  SceneStatus setScale(double scale);
  double linkPadding(const std::string& link_name) const;  // NaN for an unknown link
  double linkScale(const std::string& link_name) const;    // NaN for an unknown link

  // World objects. Ids share one namespace with links and attached objects.
  SceneStatus addWorldObject(const WorldObject& object);
  SceneStatus moveWorldObject(const std::string& id, const Eigen::Isometry3d& pose);
  SceneStatus removeWorldObject(const std::string& id);
  void clearWorld();
  std::vector<std::string> worldObjectIds() const;
  bool hasWorldObject(const std::string& id) const;

  // Attached objects. attachWorldObject keeps the object where it is: its pose in the link becomes
  // link_pose^-1 * object pose. detachObject puts it back into the world at link_pose * pose_in_link.
  SceneStatus attachObject(const AttachedObject& object);
  SceneStatus attachWorldObject(const std::string& id, const std::string& link_name,
                                const Eigen::Isometry3d& link_pose, const std::vector<std::string>& touch_links);
  SceneStatus detachObject(const std::string& id, const Eigen::Isometry3d& link_pose);
  SceneStatus removeAttachedObject(const std::string& id);
  std::vector<std::string> attachedObjectIds() const;
  bool hasAttachedObject(const std::string& id) const;

  // The occupancy map (occupancy_map.h) robot links and attached objects collide against (world objects do
  // not), placed in the world by map_pose; null removes it. The map must not change while a scene holds it:
  // give each scene a snapshot. Copies of the scene share it. Allowed-collision entries do not apply to it.
  void setOccupancyMap(std::shared_ptr<const OccupancyMap> map,
                       const Eigen::Isometry3d& map_pose = Eigen::Isometry3d::Identity());
  std::shared_ptr<const OccupancyMap> occupancyMap() const;

  // Every body's own shapes (neither padded nor scaled) placed in the world at link_poses: robot links, attached
  // objects, then world objects. A depth sensor's self filter masks these.
  std::vector<PlacedShape> bodyShapes(const std::vector<Eigen::Isometry3d>& link_poses) const;

  // Queries. link_poses[i] is the world pose of link i. A pose vector of the wrong size is a programming
  // error and throws std::invalid_argument (as std::vector::at would); everything else is a result.
  bool isColliding(const std::vector<Eigen::Isometry3d>& link_poses,
                   CollisionScope scope = CollisionScope::kAll) const;
  CollisionReport checkCollision(const std::vector<Eigen::Isometry3d>& link_poses,
                                 const CollisionRequest& request = CollisionRequest()) const;
  // distance() leaves the occupancy map out (checkCollision and isColliding include it).
  DistanceReport distance(const std::vector<Eigen::Isometry3d>& link_poses,
                          CollisionScope scope = CollisionScope::kAll) const;

  // The collision pre-check of a motion bounded by `bound` (the links start at link_poses): the largest fraction
  // u <= cap of it over which isColliding would certainly report nothing, proven with spheres that contain every
  // robot shape (fitted when the shape is built, on the padded and scaled geometry FCL collides) against the world's
  // boxes, spheres and cylinders, the oriented box of any other world shape and the box around the occupancy map's
  // occupied cells, and between the bodies of every self pair, with a 0.1 mm margin for rounding. The proof may fall
  // short of the best the spheres allow by up to `tolerance` (opening fewer spheres). Throws std::invalid_argument
  // on a pose vector or bound of the wrong size, a bound < 0 or a tolerance < 0.
  SphereCertificate precheckMotion(const std::vector<Eigen::Isometry3d>& link_poses, const LinkMotionBound& bound,
                                   double cap = 1.0, double tolerance = 0.0) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixdof_core
