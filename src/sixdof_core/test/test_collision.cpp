// CollisionScene on the provisional primitive arm (parsed here with urdfdom): construction errors, self
// collision, the allowed collision matrix, the three queries agreeing on random states, and thread safety.
// World objects are in test_collision_world.cpp, contacts and distances in test_collision_distance.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "test_collision_helpers.h"

namespace sixdof_core {
namespace {

using namespace collision_test;  // NOLINT(build/namespaces): the shared probes and arm of the three files

TEST(CollisionScene, BadConstructionThrows) {
  const auto arm = loadArm();
  EXPECT_THROW(CollisionScene(arm.links, {{"link1", "no_such_link"}}), std::invalid_argument);
  auto duplicated = arm.links;
  duplicated.push_back(arm.links.front());
  EXPECT_THROW(CollisionScene(duplicated, {}), std::invalid_argument);
  LinkGeometry bad;
  bad.link_name = "bad";
  bad.shapes.push_back(PlacedShape{box(0.1, -0.1, 0.1), Eigen::Isometry3d::Identity()});
  EXPECT_THROW(CollisionScene({bad}, {}), std::invalid_argument);
  LinkGeometry missing;
  missing.link_name = "missing";
  missing.shapes.push_back(PlacedShape{mesh("/nonexistent/mesh.stl"), Eigen::Isometry3d::Identity()});
  EXPECT_THROW(CollisionScene({missing}, {}), std::invalid_argument);
  CollisionSceneOptions options;
  options.link_padding = -0.01;
  EXPECT_THROW(CollisionScene(arm.links, {}, options), std::invalid_argument);
}

TEST(CollisionScene, WrongPoseCountThrows) {
  const auto arm = loadArm();
  const CollisionScene scene(arm.links, disabledPairs(arm));
  EXPECT_THROW(scene.isColliding({}), std::invalid_argument);
}

TEST(CollisionScene, HomeIsFreeFoldedArmCollides) {
  const auto arm = loadArm();
  const CollisionScene scene(arm.links, disabledPairs(arm));
  EXPECT_FALSE(scene.isColliding(arm.poses({})));
  EXPECT_FALSE(scene.isColliding(arm.poses(topDown(arm, 0.4, 0.2))));

  // Forearm folded down along the upper arm.
  const auto folded = arm.poses({{"joint3", 1.6}});
  EXPECT_TRUE(scene.isColliding(folded));
  const CollisionReport report = scene.checkCollision(folded);
  EXPECT_TRUE(report.colliding);
  EXPECT_TRUE(hasPair(report, "link2", "link4"));
  for (const Contact& c : report.contacts) {
    EXPECT_EQ(c.type1, BodyType::kRobotLink);
    EXPECT_EQ(c.type2, BodyType::kRobotLink);
    EXPECT_GT(c.depth, 0.0);
  }
  // Upper arm thrown back and forearm folded: the wrist reaches the base.
  const CollisionReport back = scene.checkCollision(arm.poses({{"joint2", -1.92}, {"joint3", 2.6}}));
  EXPECT_TRUE(hasPair(back, "base_link", "link4"));
  EXPECT_LT(scene.distance(folded, CollisionScope::kSelf).distance, 0.0);
}


void expectQueriesAgree(const sixdof_test::UrdfArm& arm, const CollisionScene& scene) {
  int colliding = 0;
  const int n = 1000;
  for (const auto& poses : arm.randomPoses(n, 7)) {
    const bool hit = scene.isColliding(poses);
    colliding += hit;
    EXPECT_EQ(hit, scene.checkCollision(poses).colliding);
    EXPECT_EQ(hit, scene.isColliding(poses, CollisionScope::kSelf) || scene.isColliding(poses, CollisionScope::kWorld));
    const DistanceReport d = scene.distance(poses);
    ASSERT_TRUE(d.found);
    // Touching pairs (distance ~0) may go either way.
    if (std::abs(d.distance) > 1e-6) {
      EXPECT_EQ(hit, d.distance < 0.0) << "distance " << d.distance;
    }
  }
  // Random states of this arm collide often but not always (sanity of the sampler and the model).
  EXPECT_GT(colliding, n / 10);
  EXPECT_LT(colliding, n * 9 / 10);
}

// The boolean query, the contact report and the distance (whose sign is computed without the boolean
// query's bounding-box prefilters) agree on random states, with tilted obstacles of every primitive and padded
// links too.
TEST(CollisionScene, QueriesAgreeOnRandomStates) {
  const auto arm = loadArm();
  for (const double padding : {0.0, 0.002}) {
    SCOPED_TRACE("padding " + std::to_string(padding));
    CollisionSceneOptions options;
    options.link_padding = padding;
    CollisionScene scene(arm.links, disabledPairs(arm), options);
    ASSERT_TRUE(scene.addWorldObject(object("table", box(1.2, 1.2, 0.05), at(0.3, 0, -0.025))).ok());
    ASSERT_TRUE(scene.setAllowed("base_link", "table", true).ok());
    Eigen::Isometry3d tilted = at(0.35, -0.1, 0.25);
    tilted.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    ASSERT_TRUE(scene.addWorldObject(object("tilted_box", box(0.2, 0.03, 0.12), tilted)).ok());
    tilted.translation() << 0.1, 0.35, 0.3;
    ASSERT_TRUE(scene.addWorldObject(object("tilted_cylinder", cylinder(0.03, 0.3), tilted)).ok());
    ASSERT_TRUE(scene.addWorldObject(object("ball", sphere(0.06), at(-0.2, -0.3, 0.4))).ok());
    expectQueriesAgree(arm, scene);
  }
}


TEST(CollisionScene, AllowedCollisionMatrixIsHonoured) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, disabledPairs(arm));
  const auto folded = arm.poses({{"joint3", 1.6}});
  ASSERT_TRUE(scene.isColliding(folded));
  const CollisionReport before = scene.checkCollision(folded);

  ASSERT_TRUE(scene.setAllowed("link2", "link4", true).ok());
  EXPECT_TRUE(scene.allowedCollisionMatrix().isAllowed("link4", "link2"));
  const CollisionReport after = scene.checkCollision(folded);
  EXPECT_FALSE(hasPair(after, "link2", "link4"));
  bool other_pairs = false;
  for (const Contact& c : before.contacts) {
    other_pairs |= !((c.body1 == "link2" && c.body2 == "link4") || (c.body1 == "link4" && c.body2 == "link2"));
  }
  EXPECT_EQ(after.colliding, other_pairs);
  // An explicit "not allowed" entry beats a default allow.
  ASSERT_TRUE(scene.setDefaultAllowed("link4", true).ok());
  ASSERT_TRUE(scene.setAllowed("link2", "link4", false).ok());
  EXPECT_TRUE(hasPair(scene.checkCollision(folded), "link2", "link4"));
  ASSERT_TRUE(scene.setAllowed("link2", "link4", true).ok());

  // Default-allow per object.
  ASSERT_TRUE(scene.addWorldObject(object("crate", box(0.3, 0.3, 0.3), at(0.3, 0, 0.6))).ok());
  const auto home = arm.poses({});
  EXPECT_TRUE(scene.isColliding(home, CollisionScope::kWorld));
  ASSERT_TRUE(scene.setDefaultAllowed("crate", true).ok());
  EXPECT_FALSE(scene.isColliding(home, CollisionScope::kWorld));

  const SceneStatus unknown = scene.setAllowed("link1", "ghost", true);
  EXPECT_EQ(unknown.status, SceneStatusCode::kUnknownName);
  EXPECT_NE(unknown.message.find("ghost"), std::string::npos);
  EXPECT_EQ(scene.setDefaultAllowed("ghost", true).status, SceneStatusCode::kUnknownName);
  AllowedCollisionMatrix acm = AllowedCollisionMatrix::fromDisabledPairs({{"link1", "phantom"}});
  EXPECT_EQ(scene.setAllowedCollisionMatrix(acm).status, SceneStatusCode::kUnknownName);

  // Entries of a removed object go with it.
  ASSERT_TRUE(scene.removeWorldObject("crate").ok());
  EXPECT_FALSE(scene.allowedCollisionMatrix().defaultEntry("crate").has_value());
}


TEST(CollisionScene, ConstQueriesAreThreadSafe) {
  const auto arm = loadArm();
  CollisionScene scene(arm.links, disabledPairs(arm));
  ASSERT_TRUE(scene.addWorldObject(object("table", box(1.2, 1.2, 0.05), at(0.3, 0, -0.025))).ok());
  ASSERT_TRUE(scene.addWorldObject(object("cube", mesh(writeCubeObj("thread_cube.obj")), at(0.3, 0.2, 0.3))).ok());
  ASSERT_TRUE(scene.setAllowed("base_link", "table", true).ok());
  const std::vector<std::vector<Eigen::Isometry3d>> states = arm.randomPoses(300, 3);
  std::vector<char> expected;
  for (const auto& s : states) expected.push_back(scene.isColliding(s));
  const CollisionScene& shared = scene;
  std::vector<char> results[2] = {std::vector<char>(states.size()), std::vector<char>(states.size())};
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 5; ++round) {
        for (std::size_t k = 0; k < states.size(); ++k) results[t][k] = shared.isColliding(states[k]);
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(results[0], expected);
  EXPECT_EQ(results[1], expected);
}


}  // namespace
}  // namespace sixdof_core
