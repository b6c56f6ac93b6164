// The suction cup on the World (no ROS): a vertical lift with a cup (test/data/suction_gantry.urdf, max_payload
// 0.5 kg from its sixdof_suction block) seals on a cube it touches, carries it through a lift, refuses one over the
// payload and lets go when the vacuum goes off; its configuration is read and checked.
#include <gtest/gtest.h>

#include <cmath>

#include "sixdof_sim/suction.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

using test::errorMessage;
using test::readFile;

std::string gantryUrdf() { return readFile(std::string(SIXDOF_TEST_DATA_DIR) + "/suction_gantry.urdf"); }

// A 4 cm cube of `mass` on the ground under the cup, rotated by `tilt` about x.
WorldSpec cubeWorld(double mass, double tilt = 0.0) {
  WorldSpec spec;
  ObjectSpec cube;
  cube.name = "cube";
  cube.shape.type = ShapeType::kBox;
  cube.shape.box_size = Eigen::Vector3d::Constant(0.04);
  cube.pose = Eigen::Translation3d(0.0, 0.0, 0.02) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX());
  cube.mass = mass;
  spec.objects.push_back(cube);
  return spec;
}

WorldOptions options() {
  WorldOptions o;
  o.grasp_fix_enabled = false;
  return o;
}

double cubeZ(const World& world) {
  ObjectState state;
  EXPECT_TRUE(world.objectState("cube", &state).ok());
  return state.spec.pose.translation().z();
}

// The lift to `q` (the cup's face at 0.3 + q) over 0.8 s.
void moveLift(World& world, double q) {
  ASSERT_TRUE(world.setPositionTarget("lift", q).ok());
  world.step(800);
}

TEST(Suction, HoldsAPayloadThroughALiftAndReleasesOnVacuumOff) {
  World world(gantryUrdf(), cubeWorld(0.3), options());
  ASSERT_TRUE(world.suctionAvailable());
  EXPECT_EQ(world.suctionConfig()->cup_link, "cup");
  ASSERT_TRUE(world.setVacuum(true).ok());
  moveLift(world, -0.259);  // the face 1 mm above the cube's top (z = 0.04): within contact_distance
  EXPECT_EQ(world.suctionHeld(), "cube");
  ObjectState state;
  ASSERT_TRUE(world.objectState("cube", &state).ok());
  EXPECT_EQ(state.attached_to, "cup");
  const std::vector<GraspEvent> attached = world.takeGraspEvents();
  ASSERT_EQ(attached.size(), 1u);
  EXPECT_EQ(attached[0].type, GraspEvent::Type::kAttached);
  EXPECT_EQ(attached[0].object, "cube");
  EXPECT_EQ(attached[0].palm_link, "cup");
  EXPECT_EQ(attached[0].arm, "gantry");
  EXPECT_EQ(attached[0].gripper_links, std::vector<std::string>{"cup"});

  moveLift(world, 0.0);
  std::printf("lifted 0.3 kg (payload 0.5 kg): cube at z %.4f m, cup face at 0.3 m\n", cubeZ(world));
  EXPECT_NEAR(cubeZ(world), 0.28, 0.005);
  EXPECT_EQ(world.suctionHeld(), "cube");

  ASSERT_TRUE(world.setVacuum(false).ok());
  world.step(1000);
  EXPECT_TRUE(world.suctionHeld().empty());
  EXPECT_NEAR(cubeZ(world), 0.02, 0.002);  // fell back to the ground
  const std::vector<GraspEvent> detached = world.takeGraspEvents();
  ASSERT_EQ(detached.size(), 1u);
  EXPECT_EQ(detached[0].type, GraspEvent::Type::kDetached);
  EXPECT_EQ(detached[0].object, "cube");
}

// The cup pressed onto the cube's top, as a pick puts its face on it: once held, the cube and the cup's body have no
// contacts (they would fight the constraint), and the cube keeps its place under the cup through the lift; let go,
// it collides with the cup again.
TEST(Suction, AHeldObjectDoesNotCollideWithTheCup) {
  World world(gantryUrdf(), cubeWorld(0.3), options());
  moveLift(world, -0.2605);  // the face 0.5 mm into the cube's top: pressing it
  const auto cupContacts = [&world] {
    int n = 0;
    for (const Contact& c : world.contacts())
      n += (c.body_a == "cup" && c.body_b == "cube") || (c.body_a == "cube" && c.body_b == "cup");
    return n;
  };
  EXPECT_GT(cupContacts(), 0);
  ASSERT_TRUE(world.setVacuum(true).ok());
  world.step(1);
  ASSERT_EQ(world.suctionHeld(), "cube");
  const double sealed = cubeZ(world) - (0.3 + world.jointPositions()[0]);
  moveLift(world, 0.0);
  EXPECT_EQ(cupContacts(), 0);
  EXPECT_NEAR(cubeZ(world) - (0.3 + world.jointPositions()[0]), sealed, 2e-4);
  moveLift(world, -0.2605);
  ASSERT_TRUE(world.setVacuum(false).ok());
  world.step(200);
  EXPECT_GT(cupContacts(), 0);
}

TEST(Suction, RefusesAnObjectOverThePayload) {
  World world(gantryUrdf(), cubeWorld(0.8), options());
  ASSERT_TRUE(world.setVacuum(true).ok());
  moveLift(world, -0.259);
  EXPECT_TRUE(world.suctionHeld().empty());
  EXPECT_EQ(world.suctionRefused(), "cube");
  moveLift(world, 0.0);
  EXPECT_NEAR(cubeZ(world), 0.02, 0.002);  // stayed on the ground
  EXPECT_TRUE(world.takeGraspEvents().empty());
}

TEST(Suction, NeedsTheVacuumAndASquareFace) {
  {
    World world(gantryUrdf(), cubeWorld(0.3), options());
    moveLift(world, -0.259);  // vacuum off: touching holds nothing
    EXPECT_TRUE(world.suctionHeld().empty());
  }
  // A cube tilted about x, kept so by teleporting it until the cup holds it (it would tip over), its top face 1 mm
  // under the cup's face on the cup's axis: held at 0.15 rad, within the 0.2 rad tolerance; not at 0.35 rad.
  for (const double tilt : {0.15, 0.35}) {
    World world(gantryUrdf(), cubeWorld(0.3, tilt), options());
    ASSERT_TRUE(world.setVacuum(true).ok());
    const Eigen::Isometry3d tilted =
        Eigen::Translation3d(0.0, 0.0, 0.02) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX());
    // The top face's height on the z axis: 0.02 + 0.02 / cos(tilt).
    ASSERT_TRUE(world.setPositionTarget("lift", 0.02 + 0.02 / std::cos(tilt) + 0.001 - 0.3).ok());
    for (int i = 0; i < 800 && world.suctionHeld().empty(); ++i) {
      ASSERT_TRUE(world.setObjectState("cube", tilted).ok());
      world.step(1);
    }
    EXPECT_EQ(world.suctionHeld(), tilt < 0.2 ? "cube" : "") << "tilt " << tilt;
  }
}

TEST(Suction, ConfigurationIsReadAndChecked) {
  const std::optional<SuctionConfig> yaml = parseSuctionYaml(
      "suction: {cup_link: cup, max_payload: 0.2, tilt_tolerance: 0.1, contact_distance: 0.002, controller: vac}\n",
      "grasping.yaml");
  ASSERT_TRUE(yaml);
  EXPECT_EQ(yaml->cup_link, "cup");
  EXPECT_EQ(yaml->max_payload, 0.2);
  EXPECT_EQ(yaml->controller, "vac");
  EXPECT_FALSE(parseSuctionYaml("grasp_fix: {}\n", "g.yaml"));
  auto yamlError = [](const std::string& text) {
    return errorMessage<std::invalid_argument>([&] { parseSuctionYaml(text, "g.yaml"); });
  };
  EXPECT_EQ(yamlError("suction: {cup_link: cup, max_payload: -1}"), "g.yaml: suction: 'max_payload' must be > 0 (kg)");
  EXPECT_EQ(yamlError("suction: {max_payload: 1}"), "g.yaml: suction: 'cup_link' is required");
  EXPECT_EQ(yamlError("suction: {cup_link: cup, tilt_tolerance: 2}"),
            "g.yaml: suction: 'tilt_tolerance' must be in (0, pi/2] (rad)");
  EXPECT_EQ(yamlError("suction: {cup_link: cup, contact_distance: 0.5}"),
            "g.yaml: suction: 'contact_distance' must be in (0, 0.02] (m)");
  EXPECT_EQ(yamlError("suction: {cup_link: cup, max_payload: heavy}"),
            "g.yaml: 'suction.max_payload' must be a number, got 'heavy'");
  EXPECT_NE(yamlError("suction: {cup_link: cup, lift: 1}").find("'suction.lift': unknown key"), std::string::npos);
  EXPECT_EQ(errorMessage<std::invalid_argument>([] { parseGraspingConfig("group: g\n", "g.yaml"); }),
            "g.yaml: no 'grasp_fix' or 'suction' mapping");
  const GraspingConfig both =
      parseGraspingConfig("suction: {cup_link: cup}\ngrasp_fix: {palm_link: p, gripper_links: [a, b]}\n", "g.yaml");
  EXPECT_TRUE(both.suction && both.grasp_fix);

  // The URDF block wins over options; a cup link the URDF lacks is refused naming it.
  WorldOptions o = options();
  o.suction_config = SuctionConfig();
  o.suction_config->cup_link = "nowhere";
  EXPECT_EQ(World(gantryUrdf(), WorldSpec(), o).suctionConfig()->cup_link, "cup");
  std::string urdf = gantryUrdf();
  urdf.replace(urdf.find("<cup_link>cup"), 13, "<cup_link>nowhere");
  EXPECT_EQ(errorMessage<WorldError>([&] { World world(urdf, WorldSpec(), options()); }),
            "suction: cup_link 'nowhere' is not a URDF link");
  EXPECT_EQ(World(test::robotUrdf(), WorldSpec(), test::options(false)).setVacuum(true).status,
            Status::kInvalidArgument);
}

}  // namespace
}  // namespace sixdof_sim
