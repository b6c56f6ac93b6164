// CollisionScene::precheckMotion: the spheres fitted to every robot shape contain it (so what they prove FCL
// confirms), allowed pairs and attached objects count as in isColliding, motions are bounded as LinkMotionBound
// says, and bad input is refused.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/collision.h"
#include "test_collision_helpers.h"

namespace sixdof_core {
namespace {

using namespace collision_test;  // NOLINT(build/namespaces): the collision tests' helpers

LinkMotionBound still(std::size_t links) {
  LinkMotionBound bound;
  bound.links.assign(links, {});
  return bound;
}

CollisionScene oneLink(const Shape& shape, double padding) {
  LinkGeometry link;
  link.link_name = "probe";
  link.shapes.push_back(PlacedShape{shape, at(0.01, -0.02, 0.03)});
  CollisionSceneOptions options;
  options.link_padding = padding;
  return CollisionScene({link}, {}, options);
}

// A 2 mm ball dropped at seeded random places around the link's shape: wherever the pre-check proves the state free,
// FCL finds no contact; and it proves nearly every place at least 2 cm from the shape.
void expectCovered(const Shape& shape, double padding, double extent) {
  CollisionScene scene = oneLink(shape, padding);
  ASSERT_TRUE(scene.addWorldObject(object("ball", sphere(0.002), at(0, 0, 0))).ok());
  const std::vector<Eigen::Isometry3d> poses = {Eigen::Isometry3d::Identity()};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-extent, extent);
  int far = 0, far_proven = 0;
  for (int k = 0; k < 3000; ++k) {
    ASSERT_TRUE(scene.moveWorldObject("ball", at(u(rng), u(rng), u(rng))).ok());
    const bool proven = scene.precheckMotion(poses, still(1)).proven > 0.0;
    if (proven) {
      ASSERT_FALSE(scene.isColliding(poses)) << "place " << k << " collides but was proven free";
    }
    if (scene.distance(poses).distance > 0.02) {
      ++far;
      far_proven += proven;
    }
  }
  EXPECT_GT(far, 100);
  EXPECT_GE(far_proven, 0.95 * far) << far_proven << " of " << far;
}

TEST(CollisionPrecheckTest, SpheresContainEveryShapeKind) {
  for (const double padding : {0.0, 0.01}) {
    SCOPED_TRACE("padding " + std::to_string(padding));
    expectCovered(box(0.2, 0.05, 0.1), padding, 0.2);
    expectCovered(cylinder(0.04, 0.3), padding, 0.25);
    expectCovered(sphere(0.06), padding, 0.12);
    expectCovered(mesh(writeCubeObj("precheck_cube.obj")), padding, 0.2);  // convex
    expectCovered(mesh(writeLStl("precheck_l.stl")), padding, 0.25);       // not convex: a surface for FCL
    expectCovered(mesh(descriptionDir() + "/meshes/collision/link2.stl"), padding, 0.4);  // an arm's hull
  }
}

TEST(CollisionPrecheckTest, AllowedPairsAndAttachedObjectsCountAsInIsColliding) {
  CollisionScene scene = probeScene();  // a 5 cm ball on link "probe"
  const std::vector<Eigen::Isometry3d> poses = probeAt(0, 0, 0);
  ASSERT_TRUE(scene.addWorldObject(object("wall", box(0.02, 1.0, 1.0), at(0.06, 0, 0))).ok());
  EXPECT_EQ(scene.precheckMotion(poses, still(1)).proven, 0.0);
  ASSERT_TRUE(scene.setAllowed("probe", "wall", true).ok());
  EXPECT_EQ(scene.precheckMotion(poses, still(1)).proven, 1.0);

  AttachedObject held;
  held.id = "held";
  held.link_name = "probe";
  held.pose_in_link = at(0, 0, -0.2);
  held.shapes.push_back(PlacedShape{box(0.05, 0.05, 0.05), Eigen::Isometry3d::Identity()});
  ASSERT_TRUE(scene.attachObject(held).ok());
  EXPECT_EQ(scene.precheckMotion(poses, still(1)).proven, 1.0);
  ASSERT_TRUE(scene.addWorldObject(object("block", box(0.1, 0.1, 0.1), at(0, 0, -0.3))).ok());
  EXPECT_FALSE(scene.isColliding(poses));
  EXPECT_GT(scene.precheckMotion(poses, still(1)).proven, 0.0);
  ASSERT_TRUE(scene.moveWorldObject("block", at(0, 0, -0.26)).ok());
  ASSERT_TRUE(scene.isColliding(poses));
  const SphereCertificate blocked = scene.precheckMotion(poses, still(1));
  EXPECT_EQ(blocked.proven, 0.0);
}

// A link moving at most 0.5 m over the motion, 0.1 m (less the ball and the spheres' overshoot) from a wall: the
// proof covers no more than the clearance allows, and not much less.
TEST(CollisionPrecheckTest, MotionBoundLimitsTheProof) {
  CollisionScene scene = probeScene();
  const std::vector<Eigen::Isometry3d> poses = probeAt(0, 0, 0);
  ASSERT_TRUE(scene.addWorldObject(object("wall", box(0.02, 1.0, 1.0), at(0.16, 0, 0))).ok());
  LinkMotionBound bound = still(1);
  bound.links[0].push_back({0, 0.5, 0.0, 0.0});
  const double clearance = scene.distance(poses).distance;  // 0.1 m
  const double proven = scene.precheckMotion(poses, bound).proven;
  EXPECT_LE(proven * 0.5, clearance);
  EXPECT_GT(proven * 0.5, 0.05);
  // Turning adds |p| per radian for the ball's points (at most 5 cm from the link's origin): less is proven.
  bound.links[0][0].angular = 1.0;
  EXPECT_LT(scene.precheckMotion(poses, bound).proven, proven);
  // The cap bounds the proof.
  EXPECT_EQ(scene.precheckMotion(poses, bound, 0.01).proven, 0.01);
}

// Two links moved by the same joint keep their distance: only the other terms bound how they close in.
TEST(CollisionPrecheckTest, SharedJointTermsDoNotCloseASelfPair) {
  LinkGeometry a, b;
  a.link_name = "a";
  a.shapes.push_back(PlacedShape{sphere(0.05), Eigen::Isometry3d::Identity()});
  b.link_name = "b";
  b.shapes.push_back(PlacedShape{sphere(0.05), Eigen::Isometry3d::Identity()});
  const CollisionScene scene({a, b}, {});
  const std::vector<Eigen::Isometry3d> poses = {at(0, 0, 0), at(0.15, 0, 0)};  // 5 cm apart
  LinkMotionBound bound = still(2);
  bound.links[0] = {{1, 10.0, 10.0, 10.0}};
  bound.links[1] = {{1, 10.0, 10.0, 10.0}, {2, 0.1, 0.0, 0.0}};
  const double proven = scene.precheckMotion(poses, bound).proven;
  EXPECT_GT(proven, 0.3);  // only joint 2 (0.1 m) closes them: 0.05 m takes half the motion
  EXPECT_LE(proven, 0.5);
}

TEST(CollisionPrecheckTest, BadInputIsRefused) {
  const CollisionScene scene = probeScene();
  EXPECT_THROW(scene.precheckMotion(probeAt(0, 0, 0), still(2)), std::invalid_argument);
  EXPECT_THROW(scene.precheckMotion({}, still(1)), std::invalid_argument);
  LinkMotionBound negative = still(1);
  negative.links[0].push_back({0, -1.0, 0.0, 0.0});
  EXPECT_THROW(scene.precheckMotion(probeAt(0, 0, 0), negative), std::invalid_argument);
  EXPECT_THROW(scene.precheckMotion(probeAt(0, 0, 0), still(1), 1.0, -0.1), std::invalid_argument);
  EXPECT_EQ(scene.precheckMotion(probeAt(0, 0, 0), still(1), 0.0).proven, 0.0);  // nothing asked, nothing proven
}

}  // namespace
}  // namespace sixdof_core
