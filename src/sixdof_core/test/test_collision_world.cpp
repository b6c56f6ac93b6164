// CollisionScene's world: primitive and mesh objects hit and missed by a probe with analytic answers,
// attached objects, multi-shape objects, bookkeeping errors; and the mesh loader's cache.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sixdof_core/mesh_loader.h"

#include "test_collision_helpers.h"

namespace sixdof_core {
namespace {

using namespace collision_test;  // NOLINT(build/namespaces): the shared probes and arm of the three files

TEST(CollisionScene, WorldPrimitivesHitAndMiss) {
  CollisionScene scene = probeScene();
  ASSERT_TRUE(scene.addWorldObject(object("box", box(0.2, 0.2, 0.2), at(0, 0, 0))).ok());
  // Probe sphere r = 0.05 against the box face at x = 0.1.
  EXPECT_TRUE(scene.isColliding(probeAt(0.149, 0, 0)));
  EXPECT_FALSE(scene.isColliding(probeAt(0.151, 0, 0)));
  // Corner direction: the box corner at (0.1, 0.1, 0.1) is sqrt(3) * 0.1 from the centre.
  const double corner = 0.1 + 0.05 / std::sqrt(3.0);
  EXPECT_TRUE(scene.isColliding(probeAt(corner - 0.001, corner - 0.001, corner - 0.001)));
  EXPECT_FALSE(scene.isColliding(probeAt(corner + 0.001, corner + 0.001, corner + 0.001)));
  ASSERT_TRUE(scene.removeWorldObject("box").ok());

  ASSERT_TRUE(scene.addWorldObject(object("ball", sphere(0.1), at(1, 0, 0))).ok());
  EXPECT_TRUE(scene.isColliding(probeAt(1, 0.149, 0)));
  EXPECT_FALSE(scene.isColliding(probeAt(1, 0.151, 0)));
  ASSERT_TRUE(scene.removeWorldObject("ball").ok());

  // Cylinder along z, radius 0.1, length 0.4; rotated 90 deg about x so its axis is along y.
  Eigen::Isometry3d rotated = at(0, 2, 0);
  rotated.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  ASSERT_TRUE(scene.addWorldObject(object("can", cylinder(0.1, 0.4), rotated)).ok());
  EXPECT_TRUE(scene.isColliding(probeAt(0.149, 2, 0)));
  EXPECT_FALSE(scene.isColliding(probeAt(0.151, 2, 0)));
  EXPECT_TRUE(scene.isColliding(probeAt(0, 2.249, 0)));
  EXPECT_FALSE(scene.isColliding(probeAt(0, 2.251, 0)));
  EXPECT_TRUE(scene.isColliding(probeAt(0, 2, 0.149)));
  EXPECT_FALSE(scene.isColliding(probeAt(0, 2, 0.151)));
}

TEST(CollisionScene, WorldMeshesHitAndMiss) {
  const std::string cube = writeCubeObj("cube.obj");
  const std::string l_shape = writeLStl("l_shape.stl");
  const MeshLoadResult cube_mesh = loadMesh(cube);
  ASSERT_TRUE(cube_mesh.ok()) << cube_mesh.message;
  EXPECT_TRUE(cube_mesh.mesh->convex);
  const MeshLoadResult l_mesh = loadMesh(l_shape);
  ASSERT_TRUE(l_mesh.ok()) << l_mesh.message;
  EXPECT_FALSE(l_mesh.mesh->convex);
  EXPECT_EQ(l_mesh.mesh->triangles.size(), 20u);

  CollisionScene scene = probeScene();
  ASSERT_TRUE(scene.addWorldObject(object("cube", mesh(cube), at(0, 0, 0))).ok());
  EXPECT_TRUE(scene.isColliding(probeAt(0.149, 0, 0)));
  EXPECT_FALSE(scene.isColliding(probeAt(0.151, 0, 0)));
  EXPECT_NEAR(scene.distance(probeAt(0.3, 0, 0)).distance, 0.15, kDistanceTolerance);
  // Convex meshes give a penetration depth.
  const CollisionReport report = scene.checkCollision(probeAt(0.14, 0, 0));
  ASSERT_EQ(report.contacts.size(), 1u);
  EXPECT_NEAR(report.contacts[0].depth, 0.01, kDistanceTolerance);
  ASSERT_TRUE(scene.removeWorldObject("cube").ok());

  Shape scaled = mesh(l_shape);
  scaled.mesh_scale << 2.0, 2.0, 2.0;  // L of 0.4 with the notch [0.2,0.4]x[0.2,0.4]
  ASSERT_TRUE(scene.addWorldObject(object("ell", scaled, at(0, 0, 0))).ok());
  // A non-convex mesh is a surface (as in MoveIt): hits are where the probe crosses a face.
  EXPECT_TRUE(scene.isColliding(probeAt(0.1, 0.1, 0.18)));  // through the top face at z = 0.2
  EXPECT_TRUE(scene.isColliding(probeAt(0.3, 0.17, 0.1)));  // through the inner face y = 0.2
  EXPECT_TRUE(scene.isColliding(probeAt(0.17, 0.3, 0.1)));  // through the inner face x = 0.2
  EXPECT_FALSE(scene.isColliding(probeAt(0.3, 0.1, 0.26)));  // 1 cm above the top face
  EXPECT_FALSE(scene.isColliding(probeAt(0.3, 0.3, 0.1)));  // in the notch, 0.1 from both inner faces
  EXPECT_NEAR(scene.distance(probeAt(0.3, 0.3, 0.1)).distance, 0.05, kDistanceTolerance);
  // Moved and turned 90 deg about z: the notch is now [-0.4,-0.2]x[0.2,0.4] around (1, 0, 0).
  Eigen::Isometry3d moved = at(1, 0, 0);
  moved.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  ASSERT_TRUE(scene.moveWorldObject("ell", moved).ok());
  EXPECT_FALSE(scene.isColliding(probeAt(0.7, 0.3, 0.1)));
  EXPECT_TRUE(scene.isColliding(probeAt(0.83, 0.3, 0.1)));  // through the inner face x = 0.8
  const DistanceReport above = scene.distance(probeAt(0.9, 0.1, 0.3));  // 0.1 above the top face
  EXPECT_NEAR(above.distance, 0.05, kDistanceTolerance);
  EXPECT_EQ(above.body2, "ell");
  EXPECT_NEAR((above.point1 - Eigen::Vector3d(0.9, 0.1, 0.25)).norm(), 0.0, 1e-3);
  EXPECT_NEAR((above.point2 - Eigen::Vector3d(0.9, 0.1, 0.2)).norm(), 0.0, 1e-3);

  Shape broken = mesh(testing::TempDir() + "missing.stl");
  const SceneStatus missing = scene.addWorldObject(object("ghost", broken, at(0, 0, 0)));
  EXPECT_EQ(missing.status, SceneStatusCode::kMeshLoadFailed);
  EXPECT_NE(missing.message.find("missing.stl"), std::string::npos);
  EXPECT_FALSE(scene.hasWorldObject("ghost"));
}


TEST(CollisionScene, AttachedObjectMovesWithLinkAndMayTouchFingers) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, disabledPairs(arm));
  ASSERT_TRUE(scene.addWorldObject(object("table", box(1.2, 1.2, 0.05), at(0.3, 0, -0.025))).ok());
  ASSERT_TRUE(scene.setAllowed("base_link", "table", true).ok());
  const int link6 = scene.linkIndex("link6");
  const int tcp = scene.linkIndex("tcp");
  ASSERT_GE(link6, 0);
  ASSERT_GE(tcp, 0);

  // Grasp: tool down, TCP 0.2 m above the table; fingers at 0.02 squeeze a 4.2 cm wide block whose bottom
  // is 1 cm below the fingertips (their depth below the TCP is measured against a plate right under the
  // gripper, to which the fingers are the closest links).
  const auto grasp = arm.poses(topDown(arm, 0.4, 0.2));
  ASSERT_NEAR(grasp[tcp].translation().z(), 0.2, 1e-9);
  ASSERT_NEAR(grasp[tcp].linear().col(2).z(), -1.0, 1e-9);
  ASSERT_FALSE(scene.isColliding(grasp));
  CollisionScene probe(arm.links, disabledPairs(arm));
  ASSERT_TRUE(probe.addWorldObject(object("plate", box(0.05, 0.05, 0.05), at(0.4, 0, -0.025))).ok());
  const DistanceReport fingers_to_table = probe.distance(grasp, CollisionScope::kWorld);
  const bool plate_second = fingers_to_table.body2 == "plate";
  ASSERT_TRUE(plate_second || fingers_to_table.body1 == "plate");
  const std::string& lowest = plate_second ? fingers_to_table.body1 : fingers_to_table.body2;
  ASSERT_EQ(lowest.rfind("finger", 0), 0u) << lowest;
  const double tip_depth = 0.2 - fingers_to_table.distance;
  const double half_height = tip_depth + 0.01;
  WorldObject block = object("block", box(0.03, 0.042, 2 * half_height), grasp[tcp]);
  ASSERT_TRUE(scene.addWorldObject(block).ok());
  EXPECT_TRUE(hasPair(scene.checkCollision(grasp), "block", "finger1"));

  // Without touch links the fingers collide with the held block.
  ASSERT_TRUE(scene.attachWorldObject("block", "link6", grasp[link6], {}).ok());
  EXPECT_FALSE(scene.hasWorldObject("block"));
  const CollisionReport squeezed = scene.checkCollision(grasp);
  EXPECT_TRUE(hasPair(squeezed, "block", "finger1"));
  EXPECT_TRUE(hasPair(squeezed, "block", "finger2"));
  for (const Contact& c : squeezed.contacts) {
    EXPECT_EQ(c.body1 == "block", c.type1 == BodyType::kAttachedObject);
    EXPECT_EQ(c.body2 == "block", c.type2 == BodyType::kAttachedObject);
  }
  ASSERT_TRUE(scene.detachObject("block", grasp[link6]).ok());
  ASSERT_TRUE(scene.hasWorldObject("block"));

  ASSERT_TRUE(scene.attachWorldObject("block", "link6", grasp[link6], {"finger1", "finger2"}).ok());
  EXPECT_FALSE(scene.isColliding(grasp));
  EXPECT_EQ(scene.attachedObjectIds(), std::vector<std::string>{"block"});

  // Lowered so the block's bottom is 5 mm into the table while the fingertips (1 cm above the block's
  // bottom) stay 5 mm clear: only block-table collides.
  const auto into_table = arm.poses(topDown(arm, 0.4, half_height - 0.005));
  const CollisionReport hit = scene.checkCollision(into_table);
  ASSERT_TRUE(hit.colliding);
  ASSERT_EQ(hit.contacts.size(), 1u);
  EXPECT_TRUE(hasPair(hit, "block", "table"));
  EXPECT_NEAR(hit.contacts[0].depth, 0.005, kDistanceTolerance);
  EXPECT_TRUE(scene.isColliding(into_table, CollisionScope::kWorld));
  EXPECT_FALSE(scene.isColliding(into_table, CollisionScope::kSelf));
  // Just above: free, and the closest world pair is the block 5 mm above the table.
  const auto above = arm.poses(topDown(arm, 0.4, half_height + 0.005));
  EXPECT_FALSE(scene.isColliding(above));
  const DistanceReport clearance = scene.distance(above, CollisionScope::kWorld);
  EXPECT_EQ(clearance.body1, "block");
  EXPECT_EQ(clearance.body2, "table");
  EXPECT_NEAR(clearance.distance, 0.005, kDistanceTolerance);

  // Releasing it on the table keeps the pose it had in the gripper.
  ASSERT_TRUE(scene.detachObject("block", above[link6]).ok());
  const CollisionScene copy = scene;  // copies are independent
  ASSERT_TRUE(scene.removeWorldObject("block").ok());
  EXPECT_TRUE(copy.hasWorldObject("block"));
  EXPECT_FALSE(scene.hasWorldObject("block"));
  // The released block stays where the gripper left it: lowering the (empty) gripper onto it again
  // squeezes it between the fingers, while the arm away from it is free.
  EXPECT_TRUE(hasPair(copy.checkCollision(above), "block", "finger1"));
  EXPECT_FALSE(copy.isColliding(arm.poses(topDown(arm, 0.4, 0.2))));
}


TEST(CollisionScene, MultiShapeObjectsMoveAsOne) {
  CollisionScene scene = probeScene();
  // A shelf: two 0.2 m boards, one at the object origin and one 0.5 m above it.
  WorldObject shelf = object("shelf", box(0.2, 0.2, 0.02), at(1, 0, 0));
  shelf.shapes.push_back(PlacedShape{box(0.2, 0.2, 0.02), at(0, 0, 0.5)});
  ASSERT_TRUE(scene.addWorldObject(shelf).ok());
  EXPECT_TRUE(scene.isColliding(probeAt(1, 0, 0.55)));
  EXPECT_FALSE(scene.isColliding(probeAt(1, 0, 0.3)));
  Eigen::Isometry3d tipped = at(1, 0, 0);
  tipped.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // upper board now at x = 1.5
  ASSERT_TRUE(scene.moveWorldObject("shelf", tipped).ok());
  EXPECT_FALSE(scene.isColliding(probeAt(1, 0, 0.55)));
  EXPECT_TRUE(scene.isColliding(probeAt(1.5, 0, 0.1)));

  // An attached tool of two spheres, 0.3 m and 0.6 m along the probe link's x axis.
  AttachedObject tool;
  tool.id = "tool";
  tool.link_name = "probe";
  tool.pose_in_link = at(0.3, 0, 0);
  tool.shapes = {PlacedShape{sphere(0.02), Eigen::Isometry3d::Identity()}, PlacedShape{sphere(0.02), at(0.3, 0, 0)}};
  ASSERT_TRUE(scene.attachObject(tool).ok());
  ASSERT_TRUE(scene.removeWorldObject("shelf").ok());
  ASSERT_TRUE(scene.addWorldObject(object("post", cylinder(0.05, 1.0), at(0, 2, 0))).ok());
  // Link at the origin turned to face +y: the tool's far sphere sits at (0, 0.6, 0), the near one at
  // (0, 0.3, 0); the post's surface is at y = 1.95.
  Eigen::Isometry3d facing_y = at(0, 0, 0);
  facing_y.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(scene.distance({facing_y}).distance, 1.95 - 0.62, kDistanceTolerance);
  facing_y.translation().y() = 1.34;  // far sphere spans y up to 1.96
  const CollisionReport hit = scene.checkCollision({facing_y});
  ASSERT_TRUE(hit.colliding);
  EXPECT_TRUE(hasPair(hit, "tool", "post"));
  EXPECT_FALSE(hasPair(hit, "probe", "post"));
}


TEST(CollisionScene, ObjectBookkeepingErrors) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, disabledPairs(arm));
  const WorldObject cube = object("cube", box(0.04, 0.04, 0.04), at(0.4, -0.15, 0.02));
  ASSERT_TRUE(scene.addWorldObject(cube).ok());
  EXPECT_EQ(scene.addWorldObject(cube).status, SceneStatusCode::kDuplicateName);
  EXPECT_EQ(scene.addWorldObject(object("link3", sphere(0.1), at(0, 0, 0))).status, SceneStatusCode::kDuplicateName);
  WorldObject empty;
  empty.id = "empty";
  EXPECT_EQ(scene.addWorldObject(empty).status, SceneStatusCode::kInvalidShape);
  EXPECT_EQ(scene.addWorldObject(object("flat", box(0.1, 0.0, 0.1), at(0, 0, 0))).status,
            SceneStatusCode::kInvalidShape);
  EXPECT_EQ(scene.moveWorldObject("ghost", at(0, 0, 0)).status, SceneStatusCode::kUnknownName);
  EXPECT_EQ(scene.removeWorldObject("ghost").status, SceneStatusCode::kUnknownName);
  EXPECT_EQ(scene.attachWorldObject("ghost", "link6", Eigen::Isometry3d::Identity(), {}).status,
            SceneStatusCode::kUnknownName);
  const SceneStatus bad_link = scene.attachWorldObject("cube", "link9", Eigen::Isometry3d::Identity(), {});
  EXPECT_EQ(bad_link.status, SceneStatusCode::kUnknownName);
  EXPECT_NE(bad_link.message.find("link9"), std::string::npos);
  EXPECT_TRUE(scene.hasWorldObject("cube"));  // a failed attach leaves it in the world
  EXPECT_EQ(scene.attachWorldObject("cube", "link6", Eigen::Isometry3d::Identity(), {"fingerX"}).status,
            SceneStatusCode::kUnknownName);
  EXPECT_EQ(scene.detachObject("ghost", Eigen::Isometry3d::Identity()).status, SceneStatusCode::kUnknownName);
  EXPECT_EQ(scene.removeAttachedObject("ghost").status, SceneStatusCode::kUnknownName);

  // Moving an object moves its collision geometry.
  const auto home = arm.poses({});
  EXPECT_FALSE(scene.isColliding(home));
  ASSERT_TRUE(scene.moveWorldObject("cube", at(0.3, 0, 0.6)).ok());  // onto the forearm
  EXPECT_TRUE(scene.isColliding(home));
  scene.clearWorld();
  EXPECT_TRUE(scene.worldObjectIds().empty());
  EXPECT_FALSE(scene.isColliding(home));
}


TEST(MeshLoader, CachesAndReportsErrors) {
  const std::string cube = writeCubeObj("cache_cube.obj");
  const MeshLoadResult first = loadMesh(cube);
  const MeshLoadResult second = loadMesh(cube);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(first.mesh.get(), second.mesh.get());
  const MeshLoadResult scaled = loadMesh(cube, Eigen::Vector3d(2, 1, 1));
  ASSERT_TRUE(scaled.ok());
  EXPECT_NE(scaled.mesh.get(), first.mesh.get());
  double max_x = 0;
  for (const auto& v : scaled.mesh->vertices) max_x = std::max(max_x, v.x());
  EXPECT_NEAR(max_x, 0.2, 1e-6);  // assimp stores floats
  const MeshLoadResult missing = loadMesh("/no/such/file.stl");
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(missing.message.find("/no/such/file.stl"), std::string::npos);
  EXPECT_FALSE(loadMesh(cube, Eigen::Vector3d(1, 0, 1)).ok());
}

}  // namespace
}  // namespace sixdof_core
