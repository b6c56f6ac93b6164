// World: robot construction from the URDF, servos, objects, determinism, reset.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "test_helpers.h"

namespace sixdof_sim {
namespace {

using test::armJoints;
using test::linkPose;

class WorldTest : public ::testing::Test {
 protected:
  WorldTest() : world(test::robotUrdf(), loadWorldFile(test::defaultWorldPath()), test::options(false)) {}
  World world;

  // Two 4 cm cubes on the table, "top" resting on "bottom".
  void spawnStack() {
    ObjectSpec bottom;
    bottom.name = "bottom";
    bottom.shape.box_size = Eigen::Vector3d::Constant(0.04);
    bottom.pose.translation() = Eigen::Vector3d(0.3, 0.4, 0.02);
    ObjectSpec top = bottom;
    top.name = "top";
    top.pose.translation().z() = 0.06;
    ASSERT_TRUE(world.spawnObject(bottom).ok());
    ASSERT_TRUE(world.spawnObject(top).ok());
  }
};

TEST_F(WorldTest, JointsComeFromTheUrdf) {
  const std::vector<std::string> expected = {"joint1", "joint2", "joint3", "joint4",
                                             "joint5", "joint6", "finger1_joint", "finger2_joint"};
  EXPECT_EQ(world.jointNames(), expected);
  const JointInfo& finger2 = world.joints()[world.jointIndex("finger2_joint")];
  EXPECT_EQ(finger2.type, JointType::kPrismatic);
  EXPECT_EQ(finger2.mimic_of, "finger1_joint");
  EXPECT_DOUBLE_EQ(finger2.mimic_multiplier, 1.0);
  const JointInfo& joint2 = world.joints()[world.jointIndex("joint2")];
  EXPECT_DOUBLE_EQ(joint2.lower, -1.92);
  EXPECT_DOUBLE_EQ(joint2.upper, 1.92);
  EXPECT_GT(joint2.max_effort, 0.0);
  EXPECT_EQ(world.jointIndex("palm_joint"), -1);  // fixed joints are merged
  EXPECT_EQ(world.jointPositions(), world.initialJointPositions());
}

TEST_F(WorldTest, HandsOutTheModelItWasBuiltFrom) {
  // The camera renderer and the node read the robot from this model instead of parsing the URDF again.
  const sixdof_core::RobotModel& model = world.robotModel();
  EXPECT_EQ(model.rootLink(), "base_link");
  std::vector<std::string> links;
  for (const sixdof_core::LinkModel& link : model.links()) links.push_back(link.name);
  std::vector<std::string> world_links = world.linkNames();
  std::sort(links.begin(), links.end());
  std::sort(world_links.begin(), world_links.end());
  EXPECT_EQ(links, world_links);
  EXPECT_EQ(world.packageResolver().resolve("package://sixdof_description/urdf/sixdof.urdf"),
            std::string(SIXDOF_DESCRIPTION_DIR) + "/urdf/sixdof.urdf");
}

TEST_F(WorldTest, ZeroPoseForwardKinematicsMatchesTheDesign) {
  // docs/design.md: at zero the forearm is along +x, link6's z along +x and its x axis down.
  const Eigen::Isometry3d link6 = linkPose(world, "link6");
  // (1e-5: the URDF writes pi/2 with 5 decimals.)
  EXPECT_NEAR((link6.translation() - Eigen::Vector3d(0.38, 0.0, 0.6)).norm(), 0.0, 1e-5);
  EXPECT_NEAR((link6.linear().col(2) - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-5);
  EXPECT_NEAR((link6.linear().col(0) + Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-5);
  // tcp is on link6's z axis, palm is fixed to link6: both move with it.
  const Eigen::Isometry3d tcp = linkPose(world, "tcp");
  EXPECT_NEAR((link6.inverse() * tcp).translation().head<2>().norm(), 0.0, 1e-9);
  Eigen::Isometry3d pose;
  EXPECT_EQ(world.linkPose("no_such_link", &pose).status, Status::kUnknownLink);
}

TEST_F(WorldTest, ObjectsRestingOnTheTableStayPutFor10Seconds) {
  std::vector<std::pair<std::string, Eigen::Isometry3d>> start;
  world.step(500);  // settle onto the table (objects start exactly touching it)
  for (const std::string& name : world.objectNames()) {
    ObjectState state;
    ASSERT_TRUE(world.objectState(name, &state).ok());
    start.emplace_back(name, state.spec.pose);
  }
  world.step(10000);
  for (const auto& entry : start) {
    ObjectState state;
    ASSERT_TRUE(world.objectState(entry.first, &state).ok());
    const double drift = (state.spec.pose.translation() - entry.second.translation()).norm();
    const double turn = Eigen::AngleAxisd(state.spec.pose.linear() * entry.second.linear().transpose()).angle();
    EXPECT_LT(drift, 1e-3) << entry.first;
    EXPECT_LT(turn, 1e-2) << entry.first;
  }
  // And the settling itself was small: the cube sits on the table top.
  ObjectState cube;
  ASSERT_TRUE(world.objectState("red_cube", &cube).ok());
  EXPECT_NEAR(cube.spec.pose.translation().z(), 0.02, 1.5e-3);
}

TEST_F(WorldTest, ArmHoldsAPoseUnderGravity) {
  // Arm stretched out horizontally: the worst gravity load.
  const std::vector<double> q = {0.3, 1.2, -1.2, 0.5, 0.8, -0.4};
  ASSERT_TRUE(world.setJointPositions(armJoints(), q).ok());
  world.step(3000);
  const std::vector<double> now = test::armPositions(world);
  for (size_t j = 0; j < q.size(); ++j) EXPECT_NEAR(now[j], q[j], 1e-3) << armJoints()[j];
  const std::vector<double> v = world.jointVelocities();
  for (size_t j = 0; j < v.size(); ++j) EXPECT_NEAR(v[j], 0.0, 1e-3) << world.jointNames()[j];
  // The shoulder carries the arm: a clearly non-zero holding effort below its limit.
  const double effort = world.jointEfforts()[world.jointIndex("joint2")];
  EXPECT_GT(std::abs(effort), 1.0);
  EXPECT_LT(std::abs(effort), world.joints()[world.jointIndex("joint2")].max_effort);
}

TEST_F(WorldTest, JointSpaceMoveIsTrackedByTheServos) {
  const std::vector<double> q0 = test::armPositions(world);
  const std::vector<double> q1 = {0.8, 0.6, -0.9, 1.0, -0.7, 1.5};
  const double duration = 2.0;
  double max_error = 0.0;
  // Cubic from rest to rest, position + velocity feed-forward every step.
  world.setPreStepCallback([&](double t) {
    const double s = std::min(t / duration, 1.0);
    const double p = 3 * s * s - 2 * s * s * s;
    const double dp = t < duration ? (6 * s - 6 * s * s) / duration : 0.0;
    for (size_t j = 0; j < q1.size(); ++j) {
      ASSERT_TRUE(world.setPositionTarget(armJoints()[j], q0[j] + p * (q1[j] - q0[j]), dp * (q1[j] - q0[j])).ok());
    }
    const std::vector<double> q = test::armPositions(world);
    for (size_t j = 0; j < q1.size(); ++j) {
      max_error = std::max(max_error, std::abs(q[j] - (q0[j] + p * (q1[j] - q0[j]))));
    }
  });
  world.step(2500);
  const std::vector<double> q = test::armPositions(world);
  for (size_t j = 0; j < q1.size(); ++j) EXPECT_NEAR(q[j], q1[j], 1e-3) << armJoints()[j];
  // One step of lag at 1 rad/s is 1 mrad; the servo's time constant adds a few more.
  EXPECT_LT(max_error, 0.02);
}

TEST_F(WorldTest, EffortModeLetsGravityWin) {
  // No actuator torque at the elbow: the forearm (horizontal at zero) falls.
  ASSERT_TRUE(world.setEffort("joint3", 0.0).ok());
  EXPECT_EQ(world.controlMode("joint3"), JointControlMode::kEffort);
  world.step(200);
  EXPECT_GT(world.jointPositions()[world.jointIndex("joint3")], 0.05);  // +y rotation tips +x down
  EXPECT_DOUBLE_EQ(world.jointEfforts()[world.jointIndex("joint3")], 0.0);
}

TEST_F(WorldTest, AnOutOfLimitsTargetIsNamedExactly) {
  // One rounding step past the upper limit: refused, and the message tells it from the limit.
  const JointInfo& info = world.joints()[world.jointIndex("joint2")];
  const double past = std::nextafter(info.upper, 10.0);
  const Result r = world.setPositionTarget("joint2", past);
  ASSERT_EQ(r.status, Status::kOutOfLimits);
  const std::size_t at = r.message.find("target ");
  ASSERT_NE(at, std::string::npos) << r.message;
  EXPECT_EQ(std::stod(r.message.substr(at + 7)), past) << r.message;  // the value as it is, not 6 digits of it
  EXPECT_NE(r.message.find("] (by 2.2e-16)"), std::string::npos) << r.message;
  EXPECT_EQ(world.setJointPositions({"joint2"}, {past}).status, Status::kOutOfLimits);
}

TEST_F(WorldTest, VelocityModeMovesAtTheCommandedSpeed) {
  ASSERT_TRUE(world.setVelocityTarget("joint1", 0.5).ok());
  world.step(1000);
  EXPECT_NEAR(world.jointVelocities()[world.jointIndex("joint1")], 0.5, 1e-3);
  EXPECT_NEAR(world.jointPositions()[world.jointIndex("joint1")], 0.5, 0.01);
}

TEST_F(WorldTest, CommandsAreValidated) {
  EXPECT_EQ(world.setPositionTarget("nope", 0.0).status, Status::kUnknownJoint);
  EXPECT_EQ(world.setPositionTarget("joint2", 2.5).status, Status::kOutOfLimits);
  EXPECT_EQ(world.setPositionTarget("joint2", NAN).status, Status::kInvalidArgument);
  EXPECT_EQ(world.setPositionTarget("joint2", 0.1, 0.0, 1e6).status, Status::kOutOfLimits);
  EXPECT_EQ(world.setPositionTarget("finger2_joint", 0.01).status, Status::kMimicJoint);
  EXPECT_EQ(world.setEffort("joint6", 1e6).status, Status::kOutOfLimits);
  EXPECT_EQ(world.setVelocityTarget("joint1", 0.1, -1.0).status, Status::kInvalidArgument);
  const Result r = world.setJointPositions({"joint1", "joint2"}, {0.0});
  EXPECT_EQ(r.status, Status::kInvalidArgument);
  EXPECT_EQ(world.setJointPositions({"joint3"}, {3.0}).status, Status::kOutOfLimits);
  // A mimic joint may be listed if it agrees with its master.
  EXPECT_TRUE(world.setJointPositions({"finger1_joint", "finger2_joint"}, {0.03, 0.03}).ok());
  EXPECT_EQ(world.setJointPositions({"finger1_joint", "finger2_joint"}, {0.03, 0.01}).status, Status::kMimicJoint);
  EXPECT_FALSE(world.controlMode("nope").has_value());
}

TEST_F(WorldTest, MimicJointFollowsItsMaster) {
  ASSERT_TRUE(world.setPositionTarget("finger1_joint", 0.03).ok());
  world.step(1000);
  const std::vector<double> q = world.jointPositions();
  EXPECT_NEAR(q[world.jointIndex("finger1_joint")], 0.03, 1e-4);
  EXPECT_NEAR(q[world.jointIndex("finger2_joint")], 0.03, 1e-4);
}

TEST_F(WorldTest, SpawnDeleteAndTeleportObjects) {
  ObjectSpec ball;
  ball.name = "ball";
  ball.shape.type = ShapeType::kSphere;
  ball.shape.radius = 0.03;
  ball.mass = 0.2;
  ball.pose.translation() = Eigen::Vector3d(0.3, 0.3, 0.5);
  ASSERT_TRUE(world.spawnObject(ball).ok());
  EXPECT_EQ(world.spawnObject(ball).status, Status::kAlreadyExists);
  ObjectSpec bad = ball;
  bad.name = "bad";
  bad.mass = 0.0;
  const Result r = world.spawnObject(bad);
  EXPECT_EQ(r.status, Status::kInvalidArgument);
  EXPECT_NE(r.message.find("mass"), std::string::npos) << r.message;
  bad.mass = 0.1;
  bad.shape.type = ShapeType::kMesh;
  // Mesh URIs resolve with the core's PackageResolver; what it cannot resolve is refused naming the URI.
  for (const std::string uri : {"package://sixdof_description/meshes/does_not_exist.stl",
                                "package://no_such_package/meshes/box.stl", "meshes/relative.stl"}) {
    bad.shape.mesh_resource = uri;
    const Result refused = world.spawnObject(bad);
    EXPECT_EQ(refused.status, Status::kInvalidArgument) << uri;
    EXPECT_NE(refused.message.find("'" + uri + "'"), std::string::npos) << refused.message;
  }
  EXPECT_NE(world.spawnObject(bad).message.find("neither a package URI nor an absolute path"), std::string::npos);

  world.step(1000);  // falls 0.47 m onto the table and rests there
  ObjectState state;
  ASSERT_TRUE(world.objectState("ball", &state).ok());
  EXPECT_NEAR(state.spec.pose.translation().z(), 0.03, 2e-3);

  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.2, 0.4, 0.5);
  Twist twist;
  twist.linear = Eigen::Vector3d(0.0, 0.0, 1.0);
  ASSERT_TRUE(world.setObjectState("ball", pose, twist).ok());
  ASSERT_TRUE(world.objectState("ball", &state).ok());
  EXPECT_TRUE(state.spec.pose.isApprox(pose));
  EXPECT_TRUE(state.twist.linear.isApprox(twist.linear));
  EXPECT_EQ(world.setObjectState("table", pose, twist).status, Status::kStaticObject);
  EXPECT_EQ(world.setObjectState("nope", pose).status, Status::kUnknownObject);

  ASSERT_TRUE(world.deleteObject("ball").ok());
  EXPECT_FALSE(world.hasObject("ball"));
  EXPECT_EQ(world.deleteObject("ball").status, Status::kUnknownObject);
}

TEST_F(WorldTest, MeshObjectsAreConvexHullsInTheMeshFrame) {
  // A 40 mm box in millimetres whose frame origin is the centre of its bottom face.
  ObjectSpec mesh;
  mesh.name = "mesh_box";
  mesh.shape.type = ShapeType::kMesh;
  mesh.shape.mesh_resource = "package://sixdof_sim/test/data/box40_bottom_origin.stl";
  mesh.shape.mesh_scale = Eigen::Vector3d::Constant(0.001);
  mesh.mass = 0.1;
  mesh.pose.translation() = Eigen::Vector3d(0.2, 0.35, 0.1);
  ASSERT_TRUE(world.spawnObject(mesh).ok()) << world.spawnObject(mesh).message;
  world.step(1500);
  ObjectState state;
  ASSERT_TRUE(world.objectState("mesh_box", &state).ok());
  // Resting on the table: the frame (bottom face) at z = 0, upright.
  EXPECT_NEAR(state.spec.pose.translation().z(), 0.0, 2e-3);
  EXPECT_NEAR(state.spec.pose.translation().x(), 0.2, 1e-3);
  EXPECT_GT(state.spec.pose.linear()(2, 2), 0.9999);
}

TEST_F(WorldTest, MarkersDoNotCollide) {
  ObjectState marker;
  ASSERT_TRUE(world.objectState("place_marker", &marker).ok());
  EXPECT_FALSE(marker.spec.collision);
  // Drop a cube through the marker: it lands on the table, not on the marker.
  ObjectSpec cube;
  cube.name = "probe";
  cube.shape.box_size = Eigen::Vector3d::Constant(0.02);
  cube.pose.translation() = marker.spec.pose.translation() + Eigen::Vector3d(0, 0, 0.05);
  ASSERT_TRUE(world.spawnObject(cube).ok());
  world.step(1000);
  ObjectState probe;
  ASSERT_TRUE(world.objectState("probe", &probe).ok());
  EXPECT_NEAR(probe.spec.pose.translation().z(), 0.01, 1.5e-3);
  bool on_table = false;
  for (const Contact& c : world.contacts()) {
    EXPECT_NE(c.body_a, "place_marker");
    EXPECT_NE(c.body_b, "place_marker");
    on_table = on_table || (c.body_a == "table" && c.body_b == "probe") || (c.body_a == "probe" && c.body_b == "table");
  }
  EXPECT_TRUE(on_table);
}

// Objects at rest sleep (exactly still, no solver work) and wake when what they rest on goes away.
TEST_F(WorldTest, RestingObjectsSleepAndWakeWhenDisturbed) {
  ASSERT_NO_FATAL_FAILURE(spawnStack());
  world.step(3000);  // asleep after 2 s at rest
  for (const std::string& name : world.objectNames()) {
    ObjectState state;
    ASSERT_TRUE(world.objectState(name, &state).ok());
    EXPECT_EQ(state.twist.linear, Eigen::Vector3d::Zero()) << name;
    EXPECT_EQ(state.twist.angular, Eigen::Vector3d::Zero()) << name;
  }
  ASSERT_TRUE(world.deleteObject("bottom").ok());
  world.step(500);
  ObjectState state;
  ASSERT_TRUE(world.objectState("top", &state).ok());
  EXPECT_NEAR(state.spec.pose.translation().z(), 0.02, 1.5e-3);  // fell onto the table
}

// A sleeping object teleported (velocity zero) falls from its new pose; teleporting what another rests on
// wakes that one too.
TEST_F(WorldTest, SleepingObjectsWakeWhenTeleported) {
  ASSERT_NO_FATAL_FAILURE(spawnStack());
  auto height = [&](const std::string& name) {
    ObjectState state;
    EXPECT_TRUE(world.objectState(name, &state).ok());
    return state.spec.pose.translation().z();
  };
  auto still = [&](const std::string& name) {
    ObjectState state;
    EXPECT_TRUE(world.objectState(name, &state).ok());
    return state.twist.linear.isZero(0.0) && state.twist.angular.isZero(0.0);
  };
  world.step(3000);
  ASSERT_TRUE(still("top") && still("bottom"));  // asleep: exactly still
  Eigen::Isometry3d lifted = Eigen::Isometry3d::Identity();
  lifted.translation() = Eigen::Vector3d(0.3, 0.4, 0.3);
  ASSERT_TRUE(world.setObjectState("top", lifted).ok());
  world.step(1000);
  EXPECT_NEAR(height("top"), 0.06, 1.5e-3);  // fell back onto the bottom cube

  world.step(3000);
  ASSERT_TRUE(still("top") && still("bottom"));
  Eigen::Isometry3d aside = Eigen::Isometry3d::Identity();
  aside.translation() = Eigen::Vector3d(0.5, 0.4, 0.02);
  ASSERT_TRUE(world.setObjectState("bottom", aside).ok());
  world.step(500);
  EXPECT_NEAR(height("top"), 0.02, 1.5e-3);  // fell onto the table
  EXPECT_NEAR(height("bottom"), 0.02, 1.5e-3);
}

// The ground plane holds what falls off the table (its broadphase bounds end at its surface).
TEST_F(WorldTest, ObjectsOffTheTableLandOnTheGround) {
  ObjectSpec cube;
  cube.name = "falling";
  cube.shape.box_size = Eigen::Vector3d::Constant(0.04);
  cube.pose.translation() = Eigen::Vector3d(1.0, 0.9, 0.3);
  ASSERT_TRUE(world.spawnObject(cube).ok());
  world.step(1500);
  ObjectState state;
  ASSERT_TRUE(world.objectState("falling", &state).ok());
  EXPECT_NEAR(state.spec.pose.translation().z(), -0.75 + 0.02, 1.5e-3);
}

// The broadphase has room for a fixed number of bodies: beyond it a spawn is refused, naming the bound.
TEST_F(WorldTest, SpawningBeyondTheBroadphaseIsRefused) {
  ObjectSpec block;
  block.shape.box_size = Eigen::Vector3d::Constant(0.01);
  block.is_static = true;
  Result r;
  int spawned = 0;
  for (; spawned < 5000 && r.ok(); ++spawned) {
    block.name = "block_" + std::to_string(spawned);
    block.pose.translation() = Eigen::Vector3d(0.02 * (spawned % 100), 2.0 + 0.02 * (spawned / 100), 0.5);
    r = world.spawnObject(block);
  }
  EXPECT_EQ(r.status, Status::kInvalidArgument);
  EXPECT_NE(r.message.find("at most 4096 bodies"), std::string::npos) << r.message;
  EXPECT_FALSE(world.hasObject(block.name));
  EXPECT_GT(spawned, 4000);
  world.step(10);
}

// Same inputs -> bit-identical states, across instances and across reset().
TEST(WorldDeterminism, TwoWorldsAndAResetAgreeBitForBit) {
  const WorldSpec spec = loadWorldFile(test::defaultWorldPath());
  auto run = [&](World& world) {
    world.setPreStepCallback([&world](double t) {
      for (size_t j = 0; j < 6; ++j) {
        const double target = 0.4 * std::sin(2.0 * t + static_cast<double>(j));
        ASSERT_TRUE(world.setPositionTarget(armJoints()[j], target).ok());
      }
      ASSERT_TRUE(world.setPositionTarget("finger1_joint", 0.02 + 0.015 * std::sin(3.0 * t)).ok());
    });
    world.step(3000);
    return world.state();
  };
  World a(test::robotUrdf(), spec, test::options(true));
  World b(test::robotUrdf(), spec, test::options(true));
  const WorldState sa = run(a);
  const WorldState sb = run(b);
  a.reset();
  EXPECT_EQ(a.simTime(), 0.0);
  EXPECT_EQ(a.jointPositions(), a.initialJointPositions());
  const WorldState sc = run(a);
  for (const WorldState* other : {&sb, &sc}) {
    EXPECT_EQ(sa.sim_time, other->sim_time);
    EXPECT_EQ(sa.joint_positions, other->joint_positions);
    EXPECT_EQ(sa.joint_velocities, other->joint_velocities);
    ASSERT_EQ(sa.object_poses.size(), other->object_poses.size());
    for (size_t i = 0; i < sa.object_poses.size(); ++i) {
      EXPECT_TRUE(sa.object_poses[i].matrix() == other->object_poses[i].matrix());
      EXPECT_TRUE(sa.object_twists[i].linear == other->object_twists[i].linear);
      EXPECT_TRUE(sa.object_twists[i].angular == other->object_twists[i].angular);
    }
  }
  EXPECT_DOUBLE_EQ(sa.sim_time, 3.0);
}

TEST(WorldReset, RestoresObjectsAndTime) {
  World world(test::robotUrdf(), loadWorldFile(test::defaultWorldPath()), test::options(false));
  ObjectState before;
  ASSERT_TRUE(world.objectState("red_cube", &before).ok());
  ASSERT_TRUE(world.deleteObject("red_cube").ok());
  ObjectSpec extra;
  extra.name = "extra";
  extra.shape.box_size = Eigen::Vector3d::Constant(0.05);
  extra.pose.translation() = Eigen::Vector3d(0.3, 0.3, 0.2);
  ASSERT_TRUE(world.spawnObject(extra).ok());
  ASSERT_TRUE(world.setPositionTarget("joint1", 1.0).ok());
  world.step(100);
  world.reset();
  EXPECT_EQ(world.stepCount(), 0u);
  EXPECT_TRUE(world.hasObject("red_cube"));
  EXPECT_FALSE(world.hasObject("extra"));
  ObjectState after;
  ASSERT_TRUE(world.objectState("red_cube", &after).ok());
  EXPECT_TRUE(after.spec.pose.isApprox(before.spec.pose));
  world.step(100);
  EXPECT_NEAR(world.jointPositions()[0], 0.0, 1e-6);
}

TEST(WorldConstruction, BadInputIsNamed) {
  const WorldSpec spec = loadWorldFile(test::defaultWorldPath());
  WorldOptions options = test::options(false);
  options.time_step = 0.0;
  EXPECT_THROW(World(test::robotUrdf(), spec, options), WorldError);
  WorldSpec duplicate = spec;
  duplicate.objects.push_back(spec.objects.back());
  // The WorldError's message ("" when the world was built).
  const auto error = [](const std::string& urdf, const WorldSpec& world_spec) {
    return test::errorMessage<WorldError>([&] { World world(urdf, world_spec, test::options(false)); });
  };
  const std::string duplicate_error = error(test::robotUrdf(), duplicate);
  EXPECT_NE(duplicate_error.find("duplicate"), std::string::npos) << "duplicate object accepted? " << duplicate_error;
  const std::string floating_error = error(
      "<robot name='x'><link name='a'/><joint name='j' type='floating'><parent link='a'/><child link='b'/></joint>"
      "<link name='b'/></robot>",
      spec);
  EXPECT_NE(floating_error.find("'j'"), std::string::npos) << "floating joint accepted? " << floating_error;
  // Grasp fix requested without any configuration (a robot without the URDF block).
  const std::string plain_robot =
      "<robot name='r'><link name='a'/><joint name='j' type='revolute'><parent link='a'/><child link='b'/>"
      "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint><link name='b'>"
      "<inertial><mass value='1'/><inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>"
      "</robot>";
  WorldOptions no_config = test::options(true);
  no_config.grasp_fix_config.reset();
  EXPECT_THROW(World(plain_robot, spec, no_config), WorldError);
  no_config.grasp_fix_enabled = false;
  World plain(plain_robot, spec, no_config);
  EXPECT_FALSE(plain.graspFixAvailable());
  EXPECT_EQ(plain.setGraspFixEnabled(true).status, Status::kInvalidArgument);
}

}  // namespace
}  // namespace sixdof_sim
