// Conveyor belts, sources and sinks on the World (no ROS): a belt carries a resting object at its speed through
// friction, stops with it, and sources and sinks spawn, delete and count objects.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "sixdof_sim/conveyor.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

using test::readFile;

std::string gantryUrdf() { return readFile(std::string(SIXDOF_TEST_DATA_DIR) + "/suction_gantry.urdf"); }

WorldOptions gantryOptions() {
  WorldOptions o;
  o.grasp_fix_enabled = false;
  return o;
}

// A 1 m belt along x from x = 0.5 to 1.5, top face at z = 0.05, and its world.
ConveyorSpec belt(double speed) {
  ConveyorSpec c;
  c.name = "belt";
  c.size = Eigen::Vector3d(1.0, 0.3, 0.05);
  c.pose = Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.025));
  c.speed = speed;
  return c;
}

ObjectSpec cube(const std::string& name, const Eigen::Vector3d& position) {
  ObjectSpec o;
  o.name = name;
  o.shape.type = ShapeType::kBox;
  o.shape.box_size = Eigen::Vector3d::Constant(0.04);
  o.pose = Eigen::Isometry3d(Eigen::Translation3d(position));
  o.mass = 0.1;
  return o;
}

Eigen::Vector3d position(const World& world, const std::string& name) {
  ObjectState state;
  EXPECT_TRUE(world.objectState(name, &state).ok()) << name;
  return state.spec.pose.translation();
}

int steps(const World& world, double seconds) { return static_cast<int>(std::lround(seconds / world.timeStep())); }

TEST(Conveyor, MovesARestingCubeAtTheBeltSpeedAndStopsWithIt) {
  WorldSpec spec;
  spec.conveyors.push_back(belt(0.2));
  spec.objects.push_back(cube("cube", {0.6, 0.0, 0.07}));
  World world(gantryUrdf(), spec, gantryOptions());
  ASSERT_TRUE(world.hasObject("belt"));  // the belt is a static object of the world
  world.step(steps(world, 0.5));         // lands and takes up the belt's speed
  const Eigen::Vector3d a = position(world, "cube");
  world.step(steps(world, 2.0));
  const Eigen::Vector3d b = position(world, "cube");
  const double speed = (b.x() - a.x()) / 2.0;
  std::printf("belt 0.2 m/s: cube at %.5f m/s (error %.3f %%), lateral drift %.2e m\n", speed,
              100.0 * std::abs(speed - 0.2) / 0.2, std::abs(b.y() - a.y()));
  EXPECT_NEAR(speed, 0.2, 0.02 * 0.2);
  EXPECT_LT(std::abs(b.y() - a.y()), 1e-3);
  EXPECT_NEAR(b.z(), 0.07, 1e-3);

  ASSERT_TRUE(world.setConveyorSpeed("belt", 0.0).ok());
  world.step(steps(world, 0.2));
  const Eigen::Vector3d c = position(world, "cube");
  world.step(steps(world, 1.0));
  EXPECT_LT((position(world, "cube") - c).norm(), 1e-4) << "the cube rides on after the belt stopped";
  EXPECT_EQ(world.conveyorStates().at(0).speed, 0.0);
}

TEST(Conveyor, RunsAlongItsDirectionAndBackwards) {
  WorldSpec spec;
  ConveyorSpec c = belt(-0.1);
  c.pose.linear() = Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();  // x along world y
  c.pose.translation() = Eigen::Vector3d(0.0, 1.0, 0.025);
  c.direction = Eigen::Vector2d(2.0, 0.0);  // any length: used normalised
  spec.conveyors.push_back(c);
  spec.objects.push_back(cube("cube", {0.0, 1.2, 0.07}));
  World world(gantryUrdf(), spec, gantryOptions());
  EXPECT_TRUE(world.conveyorStates().at(0).velocity.isApprox(Eigen::Vector3d(0.0, -0.1, 0.0), 1e-12));
  world.step(steps(world, 0.5));
  const Eigen::Vector3d a = position(world, "cube");
  world.step(steps(world, 1.0));
  const Eigen::Vector3d b = position(world, "cube");
  EXPECT_NEAR(b.y() - a.y(), -0.1, 0.002);
  EXPECT_LT(std::abs(b.x() - a.x()), 1e-3);
}

TEST(Conveyor, SetSpeedRefusesUnknownNamesAndNonFiniteSpeedsAndTheBeltStays) {
  WorldSpec spec;
  spec.conveyors.push_back(belt(0.1));
  World world(gantryUrdf(), spec, gantryOptions());
  const Result unknown = world.setConveyorSpeed("nope", 0.1);
  EXPECT_EQ(unknown.status, Status::kUnknownObject);
  EXPECT_NE(unknown.message.find("unknown conveyor 'nope'"), std::string::npos) << unknown.message;
  const Result nan = world.setConveyorSpeed("belt", std::nan(""));
  EXPECT_EQ(nan.status, Status::kInvalidArgument);
  EXPECT_NE(nan.message.find("speed must be finite"), std::string::npos) << nan.message;
  EXPECT_EQ(world.conveyorStates().at(0).speed, 0.1);  // unchanged
  const Result deleted = world.deleteObject("belt");
  EXPECT_EQ(deleted.status, Status::kInvalidArgument);
  EXPECT_EQ(deleted.message, "object 'belt' is a conveyor's belt: it stays");
  EXPECT_EQ(world.setObjectState("belt", Eigen::Isometry3d::Identity()).status, Status::kInvalidArgument);
  EXPECT_TRUE(world.hasObject("belt"));
}

// A source feeding the belt every 0.5 s and a sink below the floor's edge: objects ride off the end, fall and are
// deleted; every spawned object is either still in the world or counted by the sink.
TEST(Conveyor, SourceSpawnsAtItsRateAndTheSinkDeletesAndCounts) {
  WorldSpec spec;
  spec.ground.z = -1.0;
  spec.conveyors.push_back(belt(0.5));
  SourceSpec source;
  source.name = "feeder";
  source.conveyor = "belt";
  source.position = Eigen::Vector2d(-0.4, 0.0);
  source.shapes = {ShapeType::kBox, ShapeType::kCylinder, ShapeType::kSphere};
  source.colors = {{1, 0, 0, 1}, {0, 0, 1, 1}};
  source.period = 0.5;
  spec.sources.push_back(source);
  SinkSpec sink;
  sink.name = "floor";
  sink.below_only = true;
  sink.below = -0.5;
  spec.sinks.push_back(sink);
  World world(gantryUrdf(), spec, gantryOptions());
  world.step(steps(world, 4.0) - 1);  // spawns at 0, 0.5, ..., 3.5 s
  EXPECT_EQ(world.sourceStates().at(0).spawned, 8);
  const double first_size = [&] {
    ObjectState state;
    EXPECT_TRUE(world.objectState("feeder_8", &state).ok());
    return state.spec.shape.type == ShapeType::kBox ? state.spec.shape.box_size.x() : 2.0 * state.spec.shape.radius;
  }();
  EXPECT_GE(first_size, 0.03);
  EXPECT_LE(first_size, 0.06);
  world.step(steps(world, 4.0));
  const long long spawned = world.sourceStates().at(0).spawned;
  const long long deleted = world.sinkStates().at(0).deleted;
  long long present = 0;
  for (const std::string& name : world.objectNames()) present += name.rfind("feeder_", 0) == 0 ? 1 : 0;
  std::printf("8 s at 0.5 m/s: %lld spawned, %lld deleted by the sink, %lld on the belt\n", spawned, deleted, present);
  EXPECT_EQ(spawned, 16);
  EXPECT_GE(deleted, 8);  // 0.9 m of belt at 0.5 m/s plus a 1.5 m fall: each object is gone within 3 s
  EXPECT_EQ(spawned, deleted + present);
  EXPECT_FALSE(world.hasObject("feeder_1"));
  const std::vector<std::string> sunk = world.takeSunkObjects();
  ASSERT_EQ(static_cast<long long>(sunk.size()), deleted);
  EXPECT_EQ(sunk.front(), "floor:feeder_1");

  world.reset();
  EXPECT_EQ(world.sourceStates().at(0).spawned, 0);
  EXPECT_EQ(world.sinkStates().at(0).deleted, 0);
  EXPECT_FALSE(world.hasObject("feeder_2"));
}

TEST(Conveyor, RandomIntervalsAreSeeded) {
  WorldSpec spec;
  spec.conveyors.push_back(belt(0.3));
  SourceSpec source;
  source.name = "feeder";
  source.conveyor = "belt";
  source.position = Eigen::Vector2d(-0.4, 0.0);
  source.lateral_jitter = 0.05;
  source.min_interval = 0.3;
  source.max_interval = 0.6;
  source.seed = 7;
  spec.sources.push_back(source);
  auto run = [&](std::uint64_t seed) {
    spec.sources[0].seed = seed;
    World world(gantryUrdf(), spec, gantryOptions());
    world.step(steps(world, 3.0));
    std::vector<Eigen::Vector3d> positions;
    for (const std::string& name : world.objectNames()) {
      if (name != "belt") positions.push_back(position(world, name));
    }
    return positions;
  };
  const auto a = run(7), b = run(7), c = run(8);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  EXPECT_GE(a.size(), 5u);   // 3 s / 0.6 s
  EXPECT_LE(a.size(), 11u);  // 3 s / 0.3 s + 1
  EXPECT_TRUE(a.size() != c.size() || a.front().y() != c.front().y());
}

// worlds/conveyor.yaml with the sixdof arm: parts ride the belt across the robot's front at its speed and the sink
// at its end takes every one that arrives. (Cylinders rock by under 0.3 mrad on a running belt, enough to vary their
// instantaneous velocity by a few per cent: their speed is measured over a second.)
TEST(Conveyor, TheConveyorWorldFeedsAndEmptiesItsBelt) {
  World world(test::robotUrdf(), loadWorldFile(std::string(SIXDOF_SIM_DIR) + "/worlds/conveyor.yaml"),
              test::options(false));
  auto parts = [&] {
    std::map<std::string, Eigen::Vector3d> out;
    for (const std::string& name : world.objectNames()) {
      if (name.rfind("part_", 0) == 0) out[name] = position(world, name);
    }
    return out;
  };
  world.step(steps(world, 19.0));
  const std::map<std::string, Eigen::Vector3d> before = parts();
  world.step(steps(world, 1.0));
  const std::map<std::string, Eigen::Vector3d> after = parts();
  const long long spawned = world.sourceStates().at(0).spawned;
  const long long deleted = world.sinkStates().at(0).deleted;
  std::printf("conveyor.yaml, 20 s: %lld parts spawned, %lld taken by the sink, %zu on the belt\n", spawned, deleted,
              after.size());
  EXPECT_GE(spawned, 7);   // intervals of at most 3 s
  EXPECT_LE(spawned, 14);  // and at least 1.5 s
  EXPECT_GE(deleted, 1);   // 0.95 m at 0.1 m/s: the first part arrives after 9.5 s
  EXPECT_EQ(spawned, deleted + static_cast<long long>(after.size()));
  for (const auto& [name, p] : after) {
    EXPECT_NEAR(p.x(), 0.45, 0.035) << name;  // on the belt, within the jitter
    if (before.count(name)) EXPECT_NEAR(p.y() - before.at(name).y(), 0.1, 0.002) << name;  // at the belt's speed
  }
}

}  // namespace
}  // namespace sixdof_sim
