// World files' conveyors, sources and sinks: read with their defaults, and every bad key named.
#include <gtest/gtest.h>

#include "sixdof_sim/world_file.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

const char* const kBelt = "conveyors:\n  - {name: belt, size: [1, 0.3, 0.05], position: [1, 0, 0.025]";

TEST(ConveyorFile, ReadsConveyorsSourcesAndSinks) {
  const WorldSpec spec = parseWorldYaml(
      std::string(kBelt) +
          ", speed: 0.2, direction: [0, 1], friction: 0.9, color: [0.1, 0.1, 0.1]}\n"
          "sources:\n"
          "  - {name: feeder, conveyor: belt, position: [-0.4, 0], shapes: [box, sphere], size: [0.03, 0.05],\n"
          "     colors: [[1, 0, 0], [0, 0, 1, 1]], mass: 0.08, interval: [0.5, 1.5], seed: 4, max_count: 100,\n"
          "     lateral_jitter: 0.02, start: 1}\n"
          "  - {name: steady, conveyor: belt, position: [0, 0], period: 2}\n"
          "sinks:\n"
          "  - {name: end, position: [1.6, 0, 0], size: [0.2, 0.5, 0.3]}\n"
          "  - {name: floor, below: -0.5}\n",
      "w.yaml");
  ASSERT_EQ(spec.conveyors.size(), 1u);
  const ConveyorSpec& c = spec.conveyors[0];
  EXPECT_EQ(c.name, "belt");
  EXPECT_EQ(c.size, Eigen::Vector3d(1, 0.3, 0.05));
  EXPECT_EQ(c.speed, 0.2);
  EXPECT_EQ(c.direction, Eigen::Vector2d(0, 1));
  EXPECT_EQ(c.friction, 0.9);
  ASSERT_EQ(spec.sources.size(), 2u);
  const SourceSpec& s = spec.sources[0];
  EXPECT_EQ(s.conveyor, "belt");
  EXPECT_EQ(s.shapes, (std::vector<ShapeType>{ShapeType::kBox, ShapeType::kSphere}));
  EXPECT_EQ(s.min_size, 0.03);
  EXPECT_EQ(s.max_size, 0.05);
  EXPECT_EQ(s.colors.size(), 2u);
  EXPECT_EQ(s.min_interval, 0.5);
  EXPECT_EQ(s.max_interval, 1.5);
  EXPECT_EQ(s.period, 0.0);
  EXPECT_EQ(s.seed, 4u);
  EXPECT_EQ(s.max_count, 100);
  EXPECT_EQ(spec.sources[1].period, 2.0);
  EXPECT_EQ(spec.sources[1].shapes, std::vector<ShapeType>{ShapeType::kBox});  // defaults
  EXPECT_EQ(spec.sources[1].min_size, 0.03);
  EXPECT_EQ(spec.sources[1].max_size, 0.06);
  ASSERT_EQ(spec.sinks.size(), 2u);
  EXPECT_FALSE(spec.sinks[0].below_only);
  EXPECT_EQ(spec.sinks[0].pose.translation(), Eigen::Vector3d(1.6, 0, 0));
  EXPECT_TRUE(spec.sinks[1].below_only);
  EXPECT_EQ(spec.sinks[1].below, -0.5);
  // The default direction is the conveyor's x axis.
  EXPECT_EQ(parseWorldYaml(std::string(kBelt) + "}\n").conveyors[0].direction, Eigen::Vector2d(1, 0));
}

std::string errorOf(const std::string& yaml) {
  return test::errorMessage<WorldFileError>([&] { parseWorldYaml(yaml, "w.yaml"); });
}

TEST(ConveyorFile, ErrorsNameTheKey) {
  const std::string belt = std::string(kBelt) + "}\n";
  const std::string source = "sources:\n  - {name: f, conveyor: belt, position: [0, 0], period: 1";
  const std::string sink = "sinks:\n  - {name: s";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {std::string(kBelt) + ", sped: 1}\n", {"w.yaml:2", "conveyors[0] (belt)", "unknown key 'sped'"}},
      {"conveyors:\n  - {name: belt, size: [1, -0.3, 0.05], position: [0, 0, 0]}\n",
       {"conveyors[0] (belt)", "'size' must be > 0 in x, y and z"}},
      {"conveyors:\n  - {name: belt, position: [0, 0, 0]}\n", {"'size' [x, y, z] is required"}},
      {std::string(kBelt) + ", direction: [0, 0]}\n", {"'direction' must be a non-zero vector"}},
      {std::string(kBelt) + ", direction: [1, 0, 0]}\n", {"'direction' must be a list of 2 numbers"}},
      {std::string(kBelt) + ", speed: fast}\n", {"'speed' must be a number, got 'fast'"}},
      {std::string(kBelt) + ", speed: .nan}\n", {"'speed' must be finite"}},
      {std::string(kBelt) + ", friction: -1}\n", {"'friction' must be >= 0"}},
      {std::string(kBelt) + "}\n  - {name: belt, size: [1, 1, 1], position: [0, 0, 0]}\n",
       {"w.yaml:3", "conveyors[1]", "duplicate name 'belt'"}},
      {"tables:\n  - {name: belt, size: [1, 1, 1], position: [0, 0, -1]}\n" + belt, {"duplicate name 'belt'"}},
      {belt + source + ", colour: [1, 0, 0]}\n", {"sources[0] (f)", "unknown key 'colour'"}},
      {belt + "sources:\n  - {name: f, conveyor: band, position: [0, 0], period: 1}\n",
       {"sources[0] (f)", "no conveyor 'band'"}},
      {belt + "sources:\n  - {name: f, position: [0, 0], period: 1}\n", {"'conveyor' (the conveyor it feeds)"}},
      {belt + "sources:\n  - {name: f, conveyor: belt, position: [0, 0]}\n",
       {"'period' (s) or 'interval' [min, max] (s) is required"}},
      {belt + source + ", interval: [1, 2]}\n", {"give 'period' or 'interval', not both"}},
      {belt + source + ", shapes: [cone]}\n", {"unknown shape 'cone' in 'shapes'"}},
      {belt + source + ", shapes: []}\n", {"'shapes' must be a non-empty list"}},
      {belt + source + ", size: [0.06, 0.03]}\n", {"'size' [min, max] must have 0 < min <= max"}},
      {belt + source + ", size: [-0.01, 0.03]}\n", {"'size' [min, max] must have 0 < min <= max"}},
      {belt + source + ", mass: 0}\n", {"'mass' must be > 0"}},
      {belt + source + ", seed: -3}\n", {"'seed' must be >= 0"}},
      {belt + source + ", max_count: -1}\n", {"'max_count' must be >= 0"}},
      {belt + "sources:\n  - {name: f, conveyor: belt, position: [0, 0], period: 0}\n", {"'period' must be > 0"}},
      {belt + "sources:\n  - {name: f, conveyor: belt, position: [0, 0], interval: [0, 1]}\n",
       {"'interval' [min, max] must have 0 < min <= max"}},
      {belt + source + "}\n  - {name: f, conveyor: belt, position: [0, 0], period: 1}\n",
       {"sources[1]", "duplicate name 'f'"}},
      {sink + ", below: -1, size: [1, 1, 1]}\n", {"sinks[0] (s)", "give either 'below'"}},
      {sink + ", position: [0, 0, 0]}\n", {"'size' [x, y, z] of the region"}},
      {sink + ", size: [1, 0, 1], position: [0, 0, 0]}\n", {"sinks[0] (s)", "'size' must be > 0 in x, y and z"}},
      {sink + ", below: low}\n", {"'below' must be a number, got 'low'"}},
      {sink + ", depth: 1}\n", {"unknown key 'depth'"}},
      {"sinks: {a: 1}\n", {"sinks", "must be a list"}},
  };
  for (const auto& [yaml, expected] : cases) {
    const std::string message = errorOf(yaml);
    ASSERT_FALSE(message.empty()) << yaml;
    for (const std::string& part : expected) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(ConveyorFile, TheWorldChecksSpecsMadeInCode) {
  const std::string urdf = test::readFile(std::string(SIXDOF_TEST_DATA_DIR) + "/suction_gantry.urdf");
  WorldOptions options;
  options.grasp_fix_enabled = false;
  WorldSpec spec;
  ConveyorSpec belt;
  belt.name = "belt";
  belt.size = Eigen::Vector3d(1, 1, 0.1);
  spec.conveyors.push_back(belt);
  SourceSpec source;
  source.name = "f";
  source.conveyor = "elsewhere";
  source.period = 1.0;
  spec.sources.push_back(source);
  EXPECT_EQ(test::errorMessage<WorldError>([&] { World world(urdf, spec, options); }),
            "world '': source 'f': no conveyor 'elsewhere'");
  spec.sources.clear();
  spec.conveyors[0].direction = Eigen::Vector2d::Zero();
  EXPECT_NE(test::errorMessage<WorldError>([&] {
              World world(urdf, spec, options);
            }).find("conveyor 'belt': 'direction' must be a non-zero vector"),
            std::string::npos);
}

}  // namespace
}  // namespace sixdof_sim
