// CollisionScene on the provisional primitive arm (parsed here with urdfdom) and on hand-built probes
// with analytic answers. Distances of primitives are compared to closed forms within 1e-4 m (FCL's
// GJK/EPA tolerances); penetration depths within 1e-4 m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include "sixdof_core/collision.h"
#include "sixdof_core/mesh_loader.h"
#include "test_collision_urdf_arm.h"
#include "test_shapes.h"

namespace sixdof_core {
namespace {

constexpr double kDistanceTolerance = 1e-4;

std::string descriptionDir() { return SIXDOF_DESCRIPTION_DIR; }

sixdof_test::UrdfArm loadArm() {
  return sixdof_test::UrdfArm(descriptionDir() + "/urdf/sixdof.urdf", descriptionDir());
}

// What the SRDF will disable: adjacent links plus the fingers, which touch when closed ("Default").
std::vector<std::pair<std::string, std::string>> disabledPairs(const sixdof_test::UrdfArm& arm) {
  auto pairs = arm.adjacent;
  pairs.emplace_back("finger1", "finger2");
  return pairs;
}

using sixdof_test::at;
using sixdof_test::box;
using sixdof_test::cylinder;
using sixdof_test::mesh;
using sixdof_test::sphere;

WorldObject object(const std::string& id, const Shape& shape, const Eigen::Isometry3d& pose) {
  WorldObject o;
  o.id = id;
  o.pose = pose;
  o.shapes.push_back(PlacedShape{shape, Eigen::Isometry3d::Identity()});
  return o;
}

// One link "probe" carrying a 5 cm sphere at its origin.
CollisionScene probeScene() {
  LinkGeometry probe;
  probe.link_name = "probe";
  probe.shapes.push_back(PlacedShape{sphere(0.05), Eigen::Isometry3d::Identity()});
  return CollisionScene({probe}, {});
}

std::vector<Eigen::Isometry3d> probeAt(double x, double y, double z) { return {at(x, y, z)}; }

// A 0.2 m cube centred at the origin, as an OBJ file.
std::string writeCubeObj(const std::string& name) {
  const std::string path = testing::TempDir() + name;
  std::ofstream f(path);
  for (int i = 0; i < 8; ++i) {
    f << "v " << ((i & 1) ? 0.1 : -0.1) << " " << ((i & 2) ? 0.1 : -0.1) << " " << ((i & 4) ? 0.1 : -0.1) << "\n";
  }
  // Faces as quads (assimp triangulates), outward winding.
  f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return path;
}

// An L-shaped prism (not convex) as ASCII STL: the union of [0,0.2]x[0,0.1]x[0,0.1] and
// [0,0.1]x[0,0.2]x[0,0.1]; the notch [0.1,0.2]x[0.1,0.2] is empty.
std::string writeLStl(const std::string& name) {
  const std::string path = testing::TempDir() + name;
  const std::vector<Eigen::Vector2d> outline = {{0, 0}, {0.2, 0}, {0.2, 0.1}, {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
  std::ofstream f(path);
  f << "solid L\n";
  auto tri = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    f << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\nouter loop\n";
    for (const auto& p : {a, b, c}) f << "vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    f << "endloop\nendfacet\n";
  };
  auto v = [&](int i, double z) { return Eigen::Vector3d(outline[i].x(), outline[i].y(), z); };
  // Bottom and top as fans from the corner (0,0) and (0.1,0.1): two convex quads each.
  const std::vector<std::array<int, 4>> quads = {{0, 1, 2, 3}, {0, 3, 4, 5}};
  for (const auto& q : quads) {
    tri(v(q[0], 0), v(q[2], 0), v(q[1], 0));
    tri(v(q[0], 0), v(q[3], 0), v(q[2], 0));
    tri(v(q[0], 0.1), v(q[1], 0.1), v(q[2], 0.1));
    tri(v(q[0], 0.1), v(q[2], 0.1), v(q[3], 0.1));
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    tri(v(i, 0), v(j, 0), v(j, 0.1));
    tri(v(i, 0), v(j, 0.1), v(i, 0.1));
  }
  f << "endsolid L\n";
  return path;
}

// Joint values that put the tool (link6 z) straight down with the TCP at (x, 0, tcp_z): planar 2-link
// solution (upper arm and forearm both 0.3 m, shoulder 0.3 m high, from the design contract) with elbow up.
// The wrist-centre-to-TCP distance is the URDF's: at zero joints the tool points along +x from the wrist
// centre (link5's origin).
std::map<std::string, double> topDown(const sixdof_test::UrdfArm& arm, double x, double tcp_z) {
  const auto zero = arm.poses({});
  const auto at_zero = [&](const std::string& link) {
    const auto it = std::find(arm.order.begin(), arm.order.end(), link);
    return zero[it - arm.order.begin()].translation();
  };
  const double wrist_to_tcp = at_zero("tcp").x() - at_zero("link5").x();
  const double l = 0.3, shoulder = 0.3;
  const double dx = x, dz = tcp_z + wrist_to_tcp - shoulder;
  const double d = std::hypot(dx, dz);
  const double a1 = std::atan2(dz, dx) + std::acos(d / (2 * l));
  const double ex = l * std::cos(a1), ez = l * std::sin(a1);
  const double a2 = std::atan2(dz - ez, dx - ex);
  const double q2 = M_PI / 2 - a1;
  const double q3 = -a2 - q2;
  return {{"joint2", q2}, {"joint3", q3}, {"joint5", M_PI / 2 + a2}, {"finger1_joint", 0.02}};
}

bool hasPair(const CollisionReport& report, const std::string& a, const std::string& b) {
  for (const Contact& c : report.contacts) {
    if ((c.body1 == a && c.body2 == b) || (c.body1 == b && c.body2 == a)) return true;
  }
  return false;
}

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
