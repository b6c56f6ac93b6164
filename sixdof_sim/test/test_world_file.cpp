// World files: the default world's content and error messages that name the problem.

#include <gtest/gtest.h>

#include "test_helpers.h"

namespace sixdof_sim {
namespace {

const ObjectSpec* find(const WorldSpec& spec, const std::string& name) {
  for (const ObjectSpec& o : spec.objects) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

TEST(WorldFile, DefaultWorldFollowsTheDesign) {
  const WorldSpec spec = loadWorldFile(test::defaultWorldPath());
  EXPECT_EQ(spec.name, "table_top");
  EXPECT_TRUE(spec.gravity.isApprox(Eigen::Vector3d(0, 0, -9.81)));
  // The table's top face is z = 0, under the robot (x = 0) and in front of it.
  const ObjectSpec* table = find(spec, "table");
  ASSERT_NE(table, nullptr);
  EXPECT_TRUE(table->is_static);
  EXPECT_NEAR(table->pose.translation().z() + table->shape.box_size.z() / 2, 0.0, 1e-12);
  EXPECT_LT(table->pose.translation().x() - table->shape.box_size.x() / 2, 0.0);
  EXPECT_GT(table->pose.translation().x() + table->shape.box_size.x() / 2, 0.6);
  EXPECT_LT(spec.ground.z, -table->shape.box_size.z() / 2);
  // A 4 cm red_cube resting at (0.40, -0.15).
  const ObjectSpec* cube = find(spec, "red_cube");
  ASSERT_NE(cube, nullptr);
  EXPECT_EQ(cube->shape.type, ShapeType::kBox);
  EXPECT_TRUE(cube->shape.box_size.isApprox(Eigen::Vector3d::Constant(0.04)));
  EXPECT_TRUE(cube->pose.translation().isApprox(Eigen::Vector3d(0.40, -0.15, 0.02)));
  EXPECT_FALSE(cube->is_static);
  EXPECT_GT(cube->mass, 0.0);
  // The place location: a marker without collision at (0.40, 0.20).
  const ObjectSpec* marker = find(spec, "place_marker");
  ASSERT_NE(marker, nullptr);
  EXPECT_FALSE(marker->collision);
  EXPECT_TRUE(marker->pose.translation().head<2>().isApprox(Eigen::Vector2d(0.40, 0.20)));
  // Obstacles of other shapes.
  ASSERT_NE(find(spec, "blue_cylinder"), nullptr);
  EXPECT_EQ(find(spec, "blue_cylinder")->shape.type, ShapeType::kCylinder);
  ASSERT_NE(find(spec, "yellow_sphere"), nullptr);
  EXPECT_EQ(find(spec, "yellow_sphere")->shape.type, ShapeType::kSphere);
  ASSERT_NE(find(spec, "green_block"), nullptr);
}

TEST(WorldFile, ParsesEveryFieldAndShape) {
  const WorldSpec spec = parseWorldYaml(R"(
name: w
gravity: [0, 0, -1.5]
ground: {z: -1, friction: 0.5, restitution: 0.1}
tables:
  - {name: t, size: [1, 2, 0.5], position: [0, 0, -0.25], rpy: [0, 0, 0.5], friction: 0.3, color: [0.1, 0.2, 0.3]}
objects:
  - {name: b, shape: box, size: [0.1, 0.2, 0.3], position: [1, 2, 3], rpy: [0.1, 0.2, 0.3], mass: 2,
     friction: 0.4, restitution: 0.5, color: [1, 0, 0, 0.5]}
  - {name: c, shape: cylinder, radius: 0.1, length: 0.2, position: [0, 0, 1], static: true}
  - {name: s, shape: sphere, radius: 0.05, position: [0, 0, 1], mass: 0.1}
  - {name: m, shape: mesh, mesh: meshes/thing.stl, scale: [0.001, 0.001, 0.001], position: [0, 0, 1], mass: 0.1}
  - {name: k, shape: box, size: [0.1, 0.1, 0.001], position: [0, 0, 0], collision: false}
)",
                                       "inline");
  EXPECT_EQ(spec.name, "w");
  EXPECT_DOUBLE_EQ(spec.gravity.z(), -1.5);
  EXPECT_DOUBLE_EQ(spec.ground.z, -1.0);
  EXPECT_DOUBLE_EQ(spec.ground.restitution, 0.1);
  ASSERT_EQ(spec.objects.size(), 6u);
  EXPECT_TRUE(spec.objects[0].is_static);
  EXPECT_DOUBLE_EQ(spec.objects[0].color.b, 0.3);
  EXPECT_DOUBLE_EQ(spec.objects[0].color.a, 1.0);
  const ObjectSpec& b = spec.objects[1];
  // Fixed-axis rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  EXPECT_TRUE(b.pose.linear().isApprox(r));
  EXPECT_DOUBLE_EQ(b.mass, 2.0);
  EXPECT_DOUBLE_EQ(b.restitution, 0.5);
  EXPECT_EQ(spec.objects[2].shape.type, ShapeType::kCylinder);
  EXPECT_TRUE(spec.objects[2].is_static);
  EXPECT_EQ(spec.objects[3].shape.type, ShapeType::kSphere);
  EXPECT_EQ(spec.objects[4].shape.mesh_resource, "meshes/thing.stl");
  EXPECT_DOUBLE_EQ(spec.objects[4].shape.mesh_scale.x(), 0.001);
  EXPECT_FALSE(spec.objects[5].collision);
  EXPECT_TRUE(spec.objects[5].is_static);  // a marker stays where it is put
}

std::string errorOf(const std::string& yaml) {
  return test::errorMessage<WorldFileError>([&] { parseWorldYaml(yaml, "w.yaml"); });
}

// Each message names the file, the line, the entry and the problem.
TEST(WorldFile, ErrorsNameTheProblem) {
  struct Case {
    std::string yaml;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"objects:\n  - {name: a, shape: box, size: [1, 1, 1], position: [0, 0, 0], mass: 1, colour: [1, 0, 0]}\n",
       {"w.yaml:2", "objects[0] (a)", "unknown key 'colour'"}},
      {"objects:\n  - {name: a, shape: box, size: [1, 1, 1], position: [0, 0, 0]}\n",
       {"objects[0] (a)", "'mass' is required"}},
      {"objects:\n  - {name: a, shape: box, size: [1, -1, 1], position: [0, 0, 0], mass: 1}\n",
       {"objects[0] (a)", "box size must be > 0"}},
      {"objects:\n  - {name: a, shape: box, size: [1, 1], position: [0, 0, 0], mass: 1}\n",
       {"'size' must be a list of 3 numbers"}},
      {"objects:\n  - {name: a, shape: cone, position: [0, 0, 0], mass: 1}\n", {"unknown shape 'cone'"}},
      {"objects:\n  - {name: a, shape: sphere, position: [0, 0, 0], mass: 1}\n", {"a sphere needs 'radius'"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, length: 2, position: [0, 0, 0], mass: 1}\n",
       {"'length' does not apply to a sphere"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, mass: 1}\n", {"'position' [x, y, z] is required"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], mass: heavy}\n",
       {"'mass' must be a number, got 'heavy'"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], static: true, mass: 1}\n",
       {"'mass' does not apply to a static object"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], mass: 1, static: maybe}\n",
       {"'static' must be true or false"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], mass: 1, restitution: 2}\n",
       {"restitution must be in [0, 1]"}},
      {"objects:\n  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], mass: 1}\n"
       "  - {name: a, shape: sphere, radius: 0.1, position: [0, 0, 0], mass: 1}\n",
       {"w.yaml:3", "objects[1]", "duplicate name 'a'"}},
      {"tables:\n  - {name: t, size: [1, 1, 1], position: [0, 0, 0], mass: 3}\n",
       {"tables[0] (t)", "unknown key 'mass'"}},
      {"objects:\n  - {shape: sphere, radius: 0.1, position: [0, 0, 0], mass: 1}\n", {"'name' is required"}},
      {"objects: {a: 1}\n", {"objects", "must be a list"}},
      {"wrld: {}\n", {"unknown key 'wrld'"}},
      {"gravity: [0, 0]\n", {"'gravity' must be a list of 3 numbers"}},
      {"objects: [\n", {"w.yaml:", "YAML syntax error"}},
      {"", {"the file is empty"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0]}\n", {"bins[0] (b)", "'size' [x, y]"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], size: [0.1, 0.1]}\n", {"bins[0] (b)", "'position' [x, y, z]"}},
      {"bins:\n  - {name: b, position: [0, 0, 0], size: [0.1, 0.1]}\n", {"bins[0] (b)", "'color' is required"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0], size: [0.1, 0]}\n",
       {"bins[0] (b)", "'size' must be > 0"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0], size: [0.1, 0.1], wall_height: -1}\n",
       {"bins[0] (b)", "'wall_height' must be > 0"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0], size: [0.1, 0.1], wall_thickness: 0.05}\n",
       {"w.yaml:2", "bins[0] (b)", "'wall_thickness'"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0], size: [0.1, 0.1], colour: red}\n",
       {"bins[0] (b)", "unknown key 'colour'"}},
      {"bins:\n  - {name: b, color: [1, 0, 0], position: [0, 0, 0], size: [0.1, 0.1]}\n"
       "  - {name: b, color: [0, 1, 0], position: [1, 0, 0], size: [0.1, 0.1]}\n",
       {"bins[1]", "duplicate bin name 'b'"}},
      {"bins: {b: 1}\n", {"bins", "must be a list"}},
  };
  for (const Case& c : cases) {
    const std::string message = errorOf(c.yaml);
    ASSERT_FALSE(message.empty()) << "accepted: " << c.yaml;
    for (const std::string& part : c.expected) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing in: " << message;
    }
  }
}

// A bin becomes four static walls inside its footprint, in its colour, standing on position.z.
TEST(WorldFile, BinsBecomeStaticWalls) {
  const WorldSpec spec = parseWorldYaml(R"(
bins:
  - {name: red_bin, color: [0.9, 0.1, 0.1], position: [0.3, 0.2, 0.0], size: [0.2, 0.1], wall_height: 0.04,
     wall_thickness: 0.01}
)",
                                       "inline");
  ASSERT_EQ(spec.objects.size(), 4u);
  Eigen::AlignedBox3d bounds;
  for (const ObjectSpec& wall : spec.objects) {
    EXPECT_EQ(wall.name.rfind("red_bin_wall_", 0), 0u) << wall.name;
    EXPECT_TRUE(wall.is_static);
    EXPECT_TRUE(wall.collision);
    EXPECT_EQ(wall.bin, "red_bin");
    EXPECT_FALSE(wall.table);
    EXPECT_DOUBLE_EQ(wall.color.r, 0.9);
    EXPECT_NEAR(wall.pose.translation().z(), 0.02, 1e-12);
    const Eigen::Vector3d half = wall.shape.box_size / 2;
    bounds.extend(wall.pose.translation() - half);
    bounds.extend(wall.pose.translation() + half);
  }
  EXPECT_TRUE(bounds.min().isApprox(Eigen::Vector3d(0.2, 0.15, 0.0)));
  EXPECT_TRUE(bounds.max().isApprox(Eigen::Vector3d(0.4, 0.25, 0.04)));
  const ObjectSpec* x_min = find(spec, "red_bin_wall_x_min");
  ASSERT_NE(x_min, nullptr);
  EXPECT_TRUE(x_min->shape.box_size.isApprox(Eigen::Vector3d(0.01, 0.1, 0.04)));
  ASSERT_EQ(spec.bins.size(), 1u);
  EXPECT_EQ(spec.bins[0].name, "red_bin");
  EXPECT_TRUE(spec.bins[0].position.isApprox(Eigen::Vector3d(0.3, 0.2, 0.0)));
  EXPECT_TRUE(spec.bins[0].size.isApprox(Eigen::Vector2d(0.2, 0.1)));
  EXPECT_DOUBLE_EQ(spec.bins[0].wall_height, 0.04);
}

// A bin without wall_height/wall_thickness gets the documented defaults (worlds/README.md#bins); tables are
// marked as such.
TEST(WorldFile, BinDefaultsAndTables) {
  const WorldSpec spec = parseWorldYaml(R"(
tables:
  - {name: table, size: [1, 1, 0.1], position: [0.4, 0, -0.05]}
objects:
  - {name: cube, shape: box, size: [0.04, 0.04, 0.04], position: [0.4, 0, 0.02], mass: 0.1}
bins:
  - {name: b, color: [0.1, 0.2, 0.9], position: [0.3, -0.3, 0.0], size: [0.2, 0.2], yaw: 1.5}
)",
                                       "inline");
  ASSERT_EQ(spec.bins.size(), 1u);
  EXPECT_DOUBLE_EQ(spec.bins[0].wall_height, 0.03);
  EXPECT_DOUBLE_EQ(spec.bins[0].wall_thickness, 0.01);
  EXPECT_DOUBLE_EQ(spec.bins[0].yaw, 1.5);
  EXPECT_DOUBLE_EQ(spec.bins[0].color.b, 0.9);
  ASSERT_NE(find(spec, "table"), nullptr);
  EXPECT_TRUE(find(spec, "table")->table);
  EXPECT_FALSE(find(spec, "cube")->table);
  EXPECT_TRUE(find(spec, "cube")->bin.empty());
}

TEST(WorldFile, SortingWorldHasABinPerColour) {
  const WorldSpec spec = loadWorldFile(std::string(SIXDOF_SIM_DIR) + "/worlds/sorting.yaml");
  int walls = 0;
  for (const ObjectSpec& o : spec.objects) walls += o.name.find("_bin_wall_") != std::string::npos;
  EXPECT_EQ(walls, 12);
  EXPECT_EQ(spec.bins.size(), 3u);
  ASSERT_EQ(spec.cameras.size(), 1u);
}

TEST(WorldFile, MissingFileAndRelativeMeshes) {
  try {
    loadWorldFile("/nonexistent/world.yaml");
    FAIL() << "no error";
  } catch (const WorldFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/world.yaml: cannot be read"), std::string::npos);
  }
}

}  // namespace
}  // namespace sixdof_sim
