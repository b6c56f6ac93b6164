// Mass properties of shapes, what makes an <inertial> unusable, and the inertias computed for moving links.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "sixdof_core/inertia.h"
#include "sixdof_core/kinematics.h"

namespace sixdof_core {
namespace {

PlacedShape placed(const Shape& shape, const Eigen::Isometry3d& origin = Eigen::Isometry3d::Identity()) {
  return PlacedShape{shape, origin};
}

Shape box(double x, double y, double z) {
  Shape s;
  s.type = ShapeType::kBox;
  s.box_size = Eigen::Vector3d(x, y, z);
  return s;
}

// A 2 x 4 x 6 cm box as an OBJ file (faces wound outwards, or inwards), or one triangle of it.
std::string writeMesh(const std::string& name, bool inwards, bool open = false) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream out(path);
  for (int v = 0; v < 8; ++v) {
    out << "v " << (v & 1 ? 0.01 : -0.01) << " " << (v & 2 ? 0.02 : -0.02) << " " << (v & 4 ? 0.03 : -0.03) << "\n";
  }
  // Outward-wound quads of the cube (1-based vertex numbers), split into triangles.
  const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (int f = 0; f < (open ? 1 : 6); ++f) {
    const int* q = quads[f];
    for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      out << "f " << t[0] << " " << (inwards ? t[2] : t[1]) << " " << (inwards ? t[1] : t[2]) << "\n";
      if (open) break;
    }
  }
  return path;
}

TEST(MassProperties, PrimitivesHaveTheTextbookValues) {
  const MassProperties b = shapeMassProperties(placed(box(0.02, 0.04, 0.06)), 1000.0);
  EXPECT_NEAR(b.mass, 0.048, 1e-12);
  EXPECT_NEAR(b.inertia(0, 0), 0.048 * (0.04 * 0.04 + 0.06 * 0.06) / 12.0, 1e-15);
  EXPECT_NEAR(b.inertia(2, 2), 0.048 * (0.02 * 0.02 + 0.04 * 0.04) / 12.0, 1e-15);
  Shape sphere;
  sphere.type = ShapeType::kSphere;
  sphere.radius = 0.05;
  const MassProperties s = shapeMassProperties(placed(sphere), 2000.0);
  EXPECT_NEAR(s.mass, 2000.0 * 4.0 / 3.0 * M_PI * 1.25e-4, 1e-12);
  EXPECT_TRUE(s.inertia.isApprox(0.4 * s.mass * 0.0025 * Eigen::Matrix3d::Identity()));
  Shape cylinder;
  cylinder.type = ShapeType::kCylinder;
  cylinder.radius = 0.02;
  cylinder.length = 0.2;
  // Lying along x, centred at (0, 0, 0.1): the axis' moment is now ixx.
  const Eigen::Isometry3d along_x = poseFromXyzRpy(0, 0, 0.1, 0, M_PI / 2, 0);
  const MassProperties c = shapeMassProperties(placed(cylinder, along_x), 1000.0);
  EXPECT_NEAR(c.mass, 1000.0 * M_PI * 0.0004 * 0.2, 1e-12);
  EXPECT_TRUE(c.com.isApprox(Eigen::Vector3d(0, 0, 0.1)));
  EXPECT_NEAR(c.inertia(0, 0), c.mass * 0.0004 / 2.0, 1e-12);
  EXPECT_NEAR(c.inertia(1, 1), c.mass * (3 * 0.0004 + 0.04) / 12.0, 1e-12);
  EXPECT_THROW(shapeMassProperties(placed(cylinder), 0.0), std::invalid_argument);
}

TEST(MassProperties, AClosedMeshIsIntegratedAndAnOpenOneIsItsBox) {
  const MassProperties expected = shapeMassProperties(placed(box(0.02, 0.04, 0.06)), 1000.0);
  for (const bool inwards : {false, true}) {
    Shape mesh;
    mesh.type = ShapeType::kMesh;
    mesh.mesh_path = writeMesh(inwards ? "inwards.obj" : "outwards.obj", inwards);
    const MassProperties m = shapeMassProperties(placed(mesh, poseFromXyzRpy(0.1, 0, 0, 0, 0, 0)), 1000.0);
    EXPECT_NEAR(m.mass, expected.mass, 1e-8) << inwards;
    EXPECT_TRUE(m.com.isApprox(Eigen::Vector3d(0.1, 0, 0), 1e-9)) << inwards;
    // assimp reads vertices as floats: 1e-7 relative.
    EXPECT_TRUE(m.inertia.isApprox(expected.inertia, 1e-6)) << inwards << "\n" << m.inertia;
  }
  Shape open;
  open.type = ShapeType::kMesh;
  open.mesh_path = writeMesh("open.obj", false, true);
  const MassProperties o = shapeMassProperties(placed(open), 1000.0);
  EXPECT_EQ(o.mass, 0.0);  // one triangle encloses nothing: its bounding box, flat
  Shape missing = open;
  missing.mesh_path = ::testing::TempDir() + "no_such_mesh.stl";
  EXPECT_THROW(shapeMassProperties(placed(missing), 1000.0), std::invalid_argument);
}

TEST(MassProperties, PartsCombineAboutTheirCommonCentre) {
  MassProperties a = shapeMassProperties(placed(box(0.1, 0.1, 0.1), poseFromXyzRpy(-0.1, 0, 0, 0, 0, 0)), 1000.0);
  MassProperties b = shapeMassProperties(placed(box(0.1, 0.1, 0.1), poseFromXyzRpy(0.1, 0, 0, 0, 0, 0)), 1000.0);
  const MassProperties both = combineMassProperties({a, b});
  EXPECT_NEAR(both.mass, 2.0, 1e-12);
  EXPECT_TRUE(both.com.isZero(1e-12));
  EXPECT_NEAR(both.inertia(1, 1), 2 * a.inertia(1, 1) + 2 * 1.0 * 0.01, 1e-12);  // parallel axes
  EXPECT_NEAR(both.inertia(0, 0), 2 * a.inertia(0, 0), 1e-12);
}

TEST(InertialProblem, NamesWhatNoRigidBodyHas) {
  EXPECT_EQ(inertialProblem(std::nullopt), "no <inertial>");
  LinkInertial good;
  good.mass = 1.0;
  good.inertia = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
  EXPECT_EQ(inertialProblem(good), "");
  LinkInertial bad = good;
  bad.mass = 0.0;
  EXPECT_NE(inertialProblem(bad).find("mass 0 is not > 0"), std::string::npos);
  bad = good;
  bad.inertia.setZero();
  EXPECT_EQ(inertialProblem(bad), "inertia is zero");
  bad.inertia = Eigen::Vector3d(0.02, 0.0, 0.02).asDiagonal();
  EXPECT_NE(inertialProblem(bad).find("principal moment"), std::string::npos);
  bad.inertia = Eigen::Vector3d(0.01, 0.01, 0.05).asDiagonal();
  EXPECT_NE(inertialProblem(bad).find("triangle inequality"), std::string::npos);
  bad.inertia = Eigen::Vector3d(0.01, 0.01, 0.0201).asDiagonal();  // within the 1 % slack of rounded values
  EXPECT_EQ(inertialProblem(bad), "");
}

TEST(InertiaRepairs, MovingLinksGetInertiasFromCollisionThenVisualGeometryThenTheDefault) {
  const std::string urdf = R"(<robot name="r">
    <link name="base"/>
    <link name="solid"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
      <visual><geometry><sphere radius="1"/></geometry></visual></link>
    <link name="shown"><visual><geometry><sphere radius="0.1"/></geometry></visual>
      <inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
    <link name="bare"/>
    <link name="ok"><inertial><mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    </link>
    <link name="tool"/>
    <joint name="a" type="revolute"><parent link="base"/><child link="solid"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="b" type="prismatic"><parent link="solid"/><child link="shown"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="c" type="continuous"><parent link="shown"/><child link="bare"/></joint>
    <joint name="d" type="revolute"><parent link="bare"/><child link="ok"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="e" type="fixed"><parent link="ok"/><child link="tool"/></joint>
  </robot>)";
  const RobotModel model(urdf, "");
  const std::vector<InertiaRepair> repairs = inertiaRepairs(model, 500.0);
  ASSERT_EQ(repairs.size(), 3u);  // not the root, not `ok`, not the fixed `tool`
  EXPECT_EQ(repairs[0].link, "solid");
  EXPECT_EQ(repairs[0].source, "collision");  // the visual sphere is not used
  EXPECT_NEAR(repairs[0].inertial.mass, 0.5, 1e-12);
  EXPECT_TRUE(repairs[0].inertial.origin.translation().isApprox(Eigen::Vector3d(0, 0, 0.05)));
  EXPECT_EQ(repairs[1].link, "shown");
  EXPECT_EQ(repairs[1].source, "visual");
  EXPECT_NE(repairs[1].problem.find("mass -1"), std::string::npos);
  EXPECT_EQ(repairs[2].link, "bare");
  EXPECT_EQ(repairs[2].source, "default");
  EXPECT_EQ(repairs[2].inertial.mass, kDefaultLinkMass);
  EXPECT_THROW(inertiaRepairs(model, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sixdof_core
