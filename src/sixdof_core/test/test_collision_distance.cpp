// CollisionScene's contacts and distances against closed forms: distances of primitives within 1e-4 m
// (FCL's GJK/EPA tolerances), penetration depths within 1e-4 m; link padding and scale.
#include <gtest/gtest.h>

#include <cmath>

#include "test_collision_helpers.h"

namespace sixdof_core {
namespace {

using namespace collision_test;  // NOLINT(build/namespaces): the shared probes and arm of the three files

TEST(CollisionScene, DistanceMatchesAnalytic) {
  CollisionScene scene = probeScene();
  EXPECT_FALSE(scene.distance(probeAt(0, 0, 0)).found);  // nothing to measure against
  ASSERT_TRUE(scene.addWorldObject(object("box", box(0.2, 0.4, 0.2), at(0, 0, 0))).ok());
  ASSERT_TRUE(scene.addWorldObject(object("ball", sphere(0.1), at(2, 0, 0))).ok());
  ASSERT_TRUE(scene.addWorldObject(object("can", cylinder(0.1, 0.4), at(0, 3, 0))).ok());

  DistanceReport d = scene.distance(probeAt(0.5, 0, 0));  // box face at x = 0.1
  ASSERT_TRUE(d.found);
  EXPECT_NEAR(d.distance, 0.35, kDistanceTolerance);
  EXPECT_EQ(d.body1, "probe");
  EXPECT_EQ(d.body2, "box");
  EXPECT_NEAR((d.point1 - Eigen::Vector3d(0.45, 0, 0)).norm(), 0.0, 1e-3);
  EXPECT_NEAR((d.point2 - Eigen::Vector3d(0.1, 0, 0)).norm(), 0.0, 1e-3);

  d = scene.distance(probeAt(0.5, 0.5, 0.3));  // box edge/corner region: nearest point (0.1, 0.2, 0.1)
  EXPECT_NEAR(d.distance, Eigen::Vector3d(0.4, 0.3, 0.2).norm() - 0.05, kDistanceTolerance);

  d = scene.distance(probeAt(1.6, 0, 0.3));  // ball centre (2, 0, 0)
  EXPECT_EQ(d.body2, "ball");
  EXPECT_NEAR(d.distance, 0.5 - 0.15, kDistanceTolerance);

  d = scene.distance(probeAt(0.5, 3, 0.1));  // can side: 0.5 - 0.1 - 0.05
  EXPECT_EQ(d.body2, "can");
  EXPECT_NEAR(d.distance, 0.35, kDistanceTolerance);
  d = scene.distance(probeAt(0, 3, 0.6));  // can cap at z = 0.2
  EXPECT_NEAR(d.distance, 0.35, kDistanceTolerance);

  // Self-distance between two spheres on two links.
  LinkGeometry a{"a", {PlacedShape{sphere(0.1), Eigen::Isometry3d::Identity()}}};
  LinkGeometry b{"b", {PlacedShape{sphere(0.2), Eigen::Isometry3d::Identity()}}};
  const CollisionScene pair({a, b}, {});
  const DistanceReport self = pair.distance({at(0, 0, 0), at(1, 0, 0)}, CollisionScope::kSelf);
  EXPECT_NEAR(self.distance, 0.7, kDistanceTolerance);
  EXPECT_NEAR(pair.distance({at(0, 0, 0), at(0.25, 0, 0)}).distance, -0.05, kDistanceTolerance);
  EXPECT_FALSE(pair.distance({at(0, 0, 0), at(1, 0, 0)}, CollisionScope::kWorld).found);
}


TEST(CollisionScene, ContactReportNamesBodiesAndDepth) {
  CollisionScene scene = probeScene();
  ASSERT_TRUE(scene.addWorldObject(object("box", box(0.2, 0.2, 0.2), at(0, 0, 0))).ok());
  const CollisionReport report = scene.checkCollision(probeAt(0.13, 0, 0));
  ASSERT_TRUE(report.colliding);
  ASSERT_EQ(report.contacts.size(), 1u);
  const Contact& c = report.contacts[0];
  EXPECT_EQ(c.body1, "probe");
  EXPECT_EQ(c.type1, BodyType::kRobotLink);
  EXPECT_EQ(c.body2, "box");
  EXPECT_EQ(c.type2, BodyType::kWorldObject);
  EXPECT_NEAR(c.depth, 0.02, kDistanceTolerance);
  EXPECT_NEAR(c.normal.x(), -1.0, 1e-3);  // from the probe (x = 0.13) towards the box
  EXPECT_NEAR(c.position.x(), 0.09, 0.011);  // within the overlap slab [0.08, 0.1]
  const DistanceReport d = scene.distance(probeAt(0.13, 0, 0));
  EXPECT_NEAR(d.distance, -0.02, kDistanceTolerance);

  // The normal points from body1 (the robot) to body2 for every geometry pairing FCL dispatches
  // differently (specialised, GJK, convex mesh, BVH mesh).
  ASSERT_TRUE(scene.removeWorldObject("box").ok());
  const std::vector<Shape> others = {box(0.2, 0.2, 0.2), sphere(0.1), cylinder(0.1, 0.2), mesh(writeCubeObj("n.obj")),
                                     mesh(writeLStl("n.stl"))};
  for (std::size_t k = 0; k < others.size(); ++k) {
    ASSERT_TRUE(scene.addWorldObject(object("other", others[k], at(0, 0, 0))).ok());
    // The L mesh's face y = 0 spans x, z in [0, 0.1]: approach it from -y there; the rest from +x.
    const auto pose = k == 4 ? probeAt(0.05, -0.04, 0.05) : probeAt(0.13, 0, 0);
    const Eigen::Vector3d towards = k == 4 ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(-1, 0, 0);
    const CollisionReport r = scene.checkCollision(pose);
    ASSERT_EQ(r.contacts.size(), 1u) << k;
    EXPECT_GT(r.contacts[0].normal.dot(towards), 0.9) << k << ": " << r.contacts[0].normal.transpose();
    ASSERT_TRUE(scene.removeWorldObject("other").ok());
  }
}


TEST(CollisionScene, PaddingAndScaleGrowLinks) {
  CollisionScene scene = probeScene();
  ASSERT_TRUE(scene.addWorldObject(object("box", box(0.2, 0.2, 0.2), at(0, 0, 0))).ok());
  const auto pose = probeAt(0.17, 0, 0);  // 0.02 gap
  EXPECT_FALSE(scene.isColliding(pose));
  EXPECT_NEAR(scene.distance(pose).distance, 0.02, kDistanceTolerance);

  ASSERT_TRUE(scene.setLinkPadding("probe", 0.015).ok());
  EXPECT_DOUBLE_EQ(scene.linkPadding("probe"), 0.015);
  EXPECT_FALSE(scene.isColliding(pose));
  EXPECT_NEAR(scene.distance(pose).distance, 0.005, kDistanceTolerance);
  ASSERT_TRUE(scene.setPadding(0.025).ok());
  EXPECT_TRUE(scene.isColliding(pose));
  EXPECT_NEAR(scene.distance(pose).distance, -0.005, kDistanceTolerance);

  ASSERT_TRUE(scene.setPadding(0.0).ok());
  ASSERT_TRUE(scene.setLinkScale("probe", 1.5).ok());  // radius 0.075: gap -0.005
  EXPECT_TRUE(scene.isColliding(pose));
  ASSERT_TRUE(scene.setScale(1.0).ok());
  EXPECT_FALSE(scene.isColliding(pose));

  EXPECT_EQ(scene.setLinkPadding("probe", -0.1).status, SceneStatusCode::kInvalidValue);
  EXPECT_EQ(scene.setLinkPadding("nope", 0.1).status, SceneStatusCode::kUnknownName);
  EXPECT_EQ(scene.setLinkScale("probe", 0.0).status, SceneStatusCode::kInvalidValue);
  EXPECT_TRUE(std::isnan(scene.linkPadding("nope")));

  // A padded convex mesh link grows by the padding on every face (corners move out diagonally).
  LinkGeometry cube_link;
  cube_link.link_name = "cube_link";
  cube_link.shapes.push_back(PlacedShape{mesh(writeCubeObj("padded_cube.obj")), Eigen::Isometry3d::Identity()});
  CollisionScene cube_scene({cube_link}, {});
  ASSERT_TRUE(cube_scene.addWorldObject(object("ball", sphere(0.05), at(0.3, 0, 0))).ok());
  const std::vector<Eigen::Isometry3d> origin = {at(0, 0, 0)};
  const Eigen::Isometry3d facing_face = at(0.3, 0, 0), facing_corner = at(-0.3, -0.3, -0.3);
  auto gapTo = [&](const Eigen::Isometry3d& ball_pose) {
    EXPECT_TRUE(cube_scene.moveWorldObject("ball", ball_pose).ok());
    return cube_scene.distance(origin).distance;
  };
  const double corner_gap = std::sqrt(3.0) * 0.2 - 0.05;
  EXPECT_NEAR(gapTo(facing_face), 0.15, kDistanceTolerance);
  EXPECT_NEAR(gapTo(facing_corner), corner_gap, kDistanceTolerance);
  ASSERT_TRUE(cube_scene.setLinkPadding("cube_link", 0.02).ok());
  EXPECT_NEAR(gapTo(facing_face), 0.13, kDistanceTolerance);
  // The padded corner moves out by 0.02 along each face normal: sqrt(3) * 0.02 along the diagonal.
  EXPECT_NEAR(gapTo(facing_corner), corner_gap - std::sqrt(3.0) * 0.02, kDistanceTolerance);

  // On the arm: padding turns a near miss into a self collision.
  const auto arm = loadArm();
  CollisionScene arm_scene(arm.links, disabledPairs(arm));
  // The largest forearm fold (1 cm steps) that is still free, then pad.
  double fold = 0.0;
  while (fold < 1.6 && !arm_scene.isColliding(arm.poses({{"joint3", fold + 0.01}}))) fold += 0.01;
  const auto near_miss = arm.poses({{"joint3", fold}});
  ASSERT_FALSE(arm_scene.isColliding(near_miss));
  const double gap = arm_scene.distance(near_miss, CollisionScope::kSelf).distance;
  ASSERT_GT(gap, 0.0);
  ASSERT_TRUE(arm_scene.setPadding(gap).ok());  // both links grow: the gap closes twice over
  EXPECT_TRUE(arm_scene.isColliding(near_miss));
}


}  // namespace
}  // namespace sixdof_core
