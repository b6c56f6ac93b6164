// The occupancy map (ray-cast insertion, masked and clipped points, clearing), the shape mask of the self filter,
// and the collision scene's robot-vs-occupancy-map checks, on hand-built probes and the real arm.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <octomap/OcTree.h>

#include "sixdof_core/collision.h"
#include "sixdof_core/occupancy_map.h"
#include "test_collision_urdf_arm.h"
#include "test_description.h"
#include "test_shapes.h"

namespace sixdof_core {
namespace {

constexpr double kResolution = 0.02;

using sixdof_test::at;
using sixdof_test::box;
using sixdof_test::cylinder;
using sixdof_test::sphere;

// A 20 x 20 cm wall of points at x = wall_x, seen from the origin.
std::vector<Eigen::Vector3d> wall(double wall_x) {
  std::vector<Eigen::Vector3d> points;
  for (double y = -0.1; y <= 0.1; y += 0.005) {
    for (double z = -0.1; z <= 0.1; z += 0.005) points.emplace_back(wall_x, y, z);
  }
  return points;
}

const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();
const std::vector<Eigen::Vector3d> kNone;

TEST(OccupancyMap, RejectsBadResolution) {
  EXPECT_THROW(OccupancyMap(0.0), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(-0.1), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(std::nan("")), std::invalid_argument);
  EXPECT_DOUBLE_EQ(OccupancyMap(kResolution).resolution(), kResolution);
}

TEST(OccupancyMap, HitsOccupyAndRaysClear) {
  OccupancyMap map(kResolution);
  EXPECT_TRUE(map.empty());
  map.insertScan(kOrigin, {Eigen::Vector3d(0.5, 0.0, 0.0)}, kNone, kNone);
  EXPECT_TRUE(map.isOccupied(Eigen::Vector3d(0.5, 0.0, 0.0)));
  EXPECT_FALSE(map.isOccupied(Eigen::Vector3d(0.25, 0.0, 0.0)));
  EXPECT_EQ(map.occupiedCells().size(), 1u);
  // The obstacle went away: rays to a wall behind it pass through its cell and clear it within a few clouds.
  for (int i = 0; i < 4; ++i) map.insertScan(kOrigin, wall(1.0), kNone, kNone);
  EXPECT_FALSE(map.isOccupied(Eigen::Vector3d(0.5, 0.0, 0.0)));
  EXPECT_TRUE(map.isOccupied(Eigen::Vector3d(1.0, 0.0, 0.0)));
  Eigen::Vector3d lo, hi;
  ASSERT_TRUE(map.occupiedBounds(&lo, &hi));
  EXPECT_NEAR(lo.x(), 1.0, 2 * kResolution);
  EXPECT_NEAR(hi.x(), 1.0, 2 * kResolution);
  for (const auto& cell : map.occupiedCells()) {
    EXPECT_NEAR(cell.center.x(), 1.0, kResolution);
    EXPECT_GE(cell.size, kResolution - 1e-9);
  }
  map.clear();
  EXPECT_TRUE(map.empty());
  EXPECT_FALSE(map.occupiedBounds(&lo, &hi));
}

TEST(OccupancyMap, MaskedPointsAreFreeAndClippedRaysOnlyClear) {
  OccupancyMap map(kResolution);
  const Eigen::Vector3d p(0.6, 0.0, 0.0);
  map.insertScan(kOrigin, {p}, kNone, kNone);
  map.insertScan(kOrigin, {p}, kNone, kNone);
  ASSERT_TRUE(map.isOccupied(p));
  // The robot now stands there: one masked cloud frees the cell at once.
  map.insertScan(kOrigin, kNone, kNone, {p});
  EXPECT_FALSE(map.isOccupied(p));
  EXPECT_TRUE(map.empty());
  // A hit sharing a cell with a masked point does not mark it.
  map.insertScan(kOrigin, {p}, kNone, {p + Eigen::Vector3d(0.001, 0.0, 0.0)});
  EXPECT_TRUE(map.empty());
  // A clipped ray clears up to its end and marks nothing.
  map.insertScan(kOrigin, {Eigen::Vector3d(0.0, 0.3, 0.0)}, kNone, kNone);
  ASSERT_FALSE(map.empty());
  for (int i = 0; i < 4; ++i) map.insertScan(kOrigin, kNone, {Eigen::Vector3d(0.0, 0.8, 0.0)}, kNone);
  EXPECT_TRUE(map.empty());
  // Non-finite points are ignored.
  map.insertScan(kOrigin, {Eigen::Vector3d(std::nan(""), 0.0, 0.0)}, kNone, kNone);
  EXPECT_TRUE(map.empty());
}

TEST(OccupancyMap, CopiesAreDeep) {
  OccupancyMap map(kResolution);
  map.insertScan(kOrigin, {Eigen::Vector3d(0.5, 0.0, 0.0)}, kNone, kNone);
  const OccupancyMap copy = map;
  map.clear();
  EXPECT_TRUE(map.empty());
  EXPECT_FALSE(copy.empty());
}

TEST(OccupancyMap, BinaryDataIsOctomapsOwn) {
  OccupancyMap map(kResolution);
  map.insertScan(kOrigin, wall(0.7), kNone, kNone);
  const std::string data = map.binaryData();
  ASSERT_FALSE(data.empty());
  // What octomap_msgs' binaryMsgToMap does with a message's data: the tree reads it back cell for cell.
  octomap::OcTree tree(kResolution);
  std::istringstream in(data);
  tree.readBinaryData(in);
  std::size_t occupied = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (tree.isNodeOccupied(*it)) ++occupied;
  }
  const auto cells = map.occupiedCells();
  EXPECT_EQ(occupied, cells.size());
  for (const auto& cell : cells) {
    const octomap::OcTreeNode* node = tree.search(cell.center.x(), cell.center.y(), cell.center.z());
    ASSERT_NE(node, nullptr);
    EXPECT_TRUE(tree.isNodeOccupied(node));
  }
}

TEST(ShapeMask, PrimitivesWithScaleAndPadding) {
  EXPECT_THROW(ShapeMask(0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(ShapeMask(1.0, -0.01), std::invalid_argument);
  ShapeMask mask(1.5, 0.01);
  ASSERT_TRUE(mask.addShape(box(0.2, 0.2, 0.2), at(1.0, 0.0, 0.0)).ok());
  ASSERT_TRUE(mask.addShape(sphere(0.1), at(0.0, 1.0, 0.0)).ok());
  ASSERT_TRUE(mask.addShape(cylinder(0.1, 0.2), at(0.0, 0.0, 1.0)).ok());
  EXPECT_EQ(mask.size(), 3u);
  // Box half extent 0.1 * 1.5 + 0.01 = 0.16.
  EXPECT_TRUE(mask.contains(Eigen::Vector3d(1.155, 0.155, 0.155)));
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(1.165, 0.0, 0.0)));
  // Sphere radius 0.16.
  EXPECT_TRUE(mask.contains(Eigen::Vector3d(0.0, 1.155, 0.0)));
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(0.1, 1.13, 0.0)));
  // Cylinder radius 0.16, half length 0.16, along z.
  EXPECT_TRUE(mask.contains(Eigen::Vector3d(0.1, 0.1, 1.155)));
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(0.0, 0.0, 1.165)));
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(0.12, 0.12, 1.0)));
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(0.5, 0.5, 0.5)));
  EXPECT_EQ(mask.addShape(box(-1.0, 0.1, 0.1), at(0, 0, 0)).status, SceneStatusCode::kInvalidShape);
}

sixdof_test::UrdfArm loadArm() {
  const std::string dir = sixdof_test::descriptionDir();
  return sixdof_test::UrdfArm(dir + "/urdf/sixdof.urdf", dir);
}

TEST(ShapeMask, ArmMeshesMaskTheirLinks) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, arm.adjacent);
  const auto poses = arm.poses({});
  ShapeMask mask(1.0, 0.02);
  for (const auto& placed : scene.bodyShapes(poses)) ASSERT_TRUE(mask.addShape(placed.shape, placed.origin).ok());
  ASSERT_GT(mask.size(), 0u);
  // Link origins lie on or inside their links' hulls, so the 2 cm padded mask holds most of them.
  std::size_t inside = 0;
  for (std::size_t i = 0; i < arm.links.size(); ++i) {
    if (arm.links[i].shapes.empty()) continue;
    const int index = scene.linkIndex(arm.links[i].link_name);
    ASSERT_GE(index, 0);
    inside += mask.contains(poses[index].translation()) ? 1 : 0;
  }
  EXPECT_GT(inside, 0u);
  EXPECT_FALSE(mask.contains(Eigen::Vector3d(3.0, 3.0, 3.0)));
}

// A robot of one box link at the origin.
CollisionScene boxRobot() {
  LinkGeometry link;
  link.link_name = "body";
  link.shapes.push_back(PlacedShape{box(0.2, 0.2, 0.2), Eigen::Isometry3d::Identity()});
  return CollisionScene({link}, {});
}

std::shared_ptr<const OccupancyMap> mapWithCellAt(const Eigen::Vector3d& p) {
  auto map = std::make_shared<OccupancyMap>(kResolution);
  map->insertScan(Eigen::Vector3d(-2.0, 0.0, 0.0), {p}, kNone, kNone);
  return map;
}

TEST(CollisionSceneOccupancy, RobotCollidesWithOccupiedCells) {
  CollisionScene scene = boxRobot();
  const std::vector<Eigen::Isometry3d> poses{Eigen::Isometry3d::Identity()};
  EXPECT_FALSE(scene.isColliding(poses));
  EXPECT_EQ(scene.occupancyMap(), nullptr);
  scene.setOccupancyMap(mapWithCellAt(Eigen::Vector3d(0.05, 0.0, 0.0)));
  EXPECT_TRUE(scene.isColliding(poses));
  EXPECT_TRUE(scene.isColliding(poses, CollisionScope::kWorld));
  EXPECT_FALSE(scene.isColliding(poses, CollisionScope::kSelf));
  CollisionRequest request;
  request.max_contacts_per_pair = 4;
  const CollisionReport report = scene.checkCollision(poses, request);
  ASSERT_TRUE(report.colliding);
  ASSERT_FALSE(report.contacts.empty());
  EXPECT_LE(report.contacts.size(), 4u);
  EXPECT_EQ(report.contacts.front().body1, "body");
  EXPECT_EQ(report.contacts.front().body2, kOccupancyMapBody);
  EXPECT_EQ(report.contacts.front().type2, BodyType::kWorldObject);
  // The robot moved away from the cell: free.
  EXPECT_FALSE(scene.isColliding({at(0.0, 0.5, 0.0)}));
  // Copies share the map; the map's pose places it.
  const CollisionScene copy = scene;
  EXPECT_TRUE(copy.isColliding(poses));
  scene.setOccupancyMap(mapWithCellAt(Eigen::Vector3d(0.05, 0.0, 0.0)), at(0.0, 0.0, 1.0));
  EXPECT_FALSE(scene.isColliding(poses));
  EXPECT_TRUE(scene.isColliding({at(0.0, 0.0, 1.0)}));
  // An empty map and no map collide with nothing.
  scene.setOccupancyMap(std::make_shared<OccupancyMap>(kResolution));
  EXPECT_FALSE(scene.isColliding({at(0.0, 0.0, 1.0)}));
  scene.setOccupancyMap(nullptr);
  EXPECT_FALSE(scene.isColliding({at(0.0, 0.0, 1.0)}));
  EXPECT_TRUE(copy.isColliding(poses));
}

TEST(CollisionSceneOccupancy, AttachedObjectsCollideWorldObjectsDoNot) {
  CollisionScene scene = boxRobot();
  const std::vector<Eigen::Isometry3d> poses{Eigen::Isometry3d::Identity()};
  AttachedObject held;
  held.id = "held";
  held.link_name = "body";
  held.pose_in_link = at(0.0, 0.0, 0.3);
  held.shapes.push_back(PlacedShape{sphere(0.05), Eigen::Isometry3d::Identity()});
  ASSERT_TRUE(scene.attachObject(held).ok());
  WorldObject table;
  table.id = "table";
  table.pose = at(1.0, 0.0, 0.0);
  table.shapes.push_back(PlacedShape{box(0.2, 0.2, 0.2), Eigen::Isometry3d::Identity()});
  ASSERT_TRUE(scene.addWorldObject(table).ok());
  scene.setOccupancyMap(mapWithCellAt(Eigen::Vector3d(1.0, 0.0, 0.0)));
  EXPECT_FALSE(scene.isColliding(poses));
  scene.setOccupancyMap(mapWithCellAt(Eigen::Vector3d(0.0, 0.0, 0.33)));
  const CollisionReport report = scene.checkCollision(poses);
  ASSERT_TRUE(report.colliding);
  EXPECT_EQ(report.contacts.front().body1, "held");
  EXPECT_EQ(report.contacts.front().body2, kOccupancyMapBody);
  // The self filter's shapes: the link, the held object at its link, the table.
  const auto shapes = scene.bodyShapes(poses);
  ASSERT_EQ(shapes.size(), 3u);
  EXPECT_TRUE(shapes[1].origin.translation().isApprox(Eigen::Vector3d(0.0, 0.0, 0.3)));
  EXPECT_TRUE(shapes[2].origin.translation().isApprox(Eigen::Vector3d(1.0, 0.0, 0.0)));
}

TEST(CollisionSceneOccupancy, ArmMeshesCollideWithCells) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, arm.adjacent);
  const auto poses = arm.poses({});
  ASSERT_FALSE(scene.isColliding(poses));
  // A cell at a link origin (inside its convex hull or right on it) collides; one far away does not.
  std::size_t hits = 0, links = 0;
  for (std::size_t i = 0; i < arm.links.size(); ++i) {
    if (arm.links[i].shapes.empty()) continue;
    ++links;
    const int index = scene.linkIndex(arm.links[i].link_name);
    scene.setOccupancyMap(mapWithCellAt(poses[index].translation()));
    hits += scene.isColliding(poses, CollisionScope::kWorld) ? 1 : 0;
  }
  EXPECT_GT(hits, links / 2);
  scene.setOccupancyMap(mapWithCellAt(Eigen::Vector3d(2.0, 2.0, 2.0)));
  EXPECT_FALSE(scene.isColliding(poses));
}

}  // namespace
}  // namespace sixdof_core
