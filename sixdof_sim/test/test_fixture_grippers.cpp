// The fixture grippers of sixdof_test_robots - prismatic fingers (parallel_hand), revolute jaws (jaw_gripper) and a
// mimic linkage whose moving links have no inertias (adaptive_gripper) - each on a gantry, with the inertias and
// the grasp geometry the setup assistant computes (sixdof_core's model layer) and the grasp fix configured from
// grasping.yaml-style options, driven by the world's gripper controller: cubes, upright cylinders and spheres of 3
// and 6 cm are held through lift and transport and released on opening.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>

#include <sixdof_core/grasp_geometry.h>
#include <sixdof_core/inertia.h>
#include <sixdof_core/kinematics.h>
#include <sixdof_core/urdf_edit.h>

#include "sixdof_sim/controllers.h"
#include "sixdof_sim/grasp_fix.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

// A gripper URDF of sixdof_test_robots with the setup assistant's computed inertias, hung from a gantry (three
// prismatic joints x, y, z whose values are the TCP's position, the TCP pointing down and closing along world y).
struct GantryGripper {
  std::string urdf;
  std::string palm;  // the gripper's root link
  sixdof_core::GraspGeometry grasp;
  std::string finger;  // its actuated finger joint
};

std::string number(double value) { return sixdof_core::urdfNumber(value); }

GantryGripper gantryGripper(const std::string& file) {
  const std::string text = test::readFile(std::string(SIXDOF_TEST_ROBOTS_DIR) + "/urdf/" + file);
  const auto model = std::make_shared<const sixdof_core::RobotModel>(text, "");
  GantryGripper out;
  out.palm = model->rootLink();
  sixdof_core::GripperQuery query;
  query.parent_link = out.palm;
  for (const auto& joint : model->joints()) {
    if (joint.type != sixdof_core::JointType::kFixed) query.joints.push_back(joint.name);
  }
  out.grasp = sixdof_core::analyzeGripper(model, query);
  out.finger = out.grasp.finger_joints.at(0).joint;
  sixdof_core::UrdfEdits edits;
  for (const auto& repair : sixdof_core::inertiaRepairs(*model)) edits.inertials[repair.link] = {repair.inertial, ""};
  out.urdf = sixdof_core::editUrdf(text, edits);
  // The TCP at the gantry's origin, z down, y along world y.
  Eigen::Isometry3d down = Eigen::Isometry3d::Identity();
  down.linear() = Eigen::Vector3d(-1, 1, -1).asDiagonal();
  const Eigen::Isometry3d mount = down * out.grasp.tcp.inverse();
  const Eigen::Vector3d rpy = sixdof_core::rpyFromRotation(mount.linear());
  std::ostringstream gantry;
  const char* const inertial =
      "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>"
      "</inertial>";
  gantry << "  <link name=\"gantry_base\"/>\n";
  const char* const axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const std::string parent = i == 0 ? "gantry_base" : std::string("gantry_") + axes[i - 1];
    gantry << "  <link name=\"gantry_" << axes[i] << "\">" << inertial << "</link>\n"
           << "  <joint name=\"gantry_" << axes[i] << "_joint\" type=\"prismatic\"><parent link=\"" << parent
           << "\"/><child link=\"gantry_" << axes[i] << "\"/><axis xyz=\"" << (i == 0) << " " << (i == 1) << " "
           << (i == 2) << "\"/><limit lower=\"-1\" upper=\"1\" effort=\"500\" velocity=\"1\"/></joint>\n";
  }
  gantry << "  <joint name=\"gantry_mount\" type=\"fixed\"><parent link=\"gantry_z\"/><child link=\"" << out.palm
         << "\"/><origin xyz=\"" << number(mount.translation().x()) << " " << number(mount.translation().y()) << " "
         << number(mount.translation().z()) << "\" rpy=\"" << number(rpy.x()) << " " << number(rpy.y()) << " "
         << number(rpy.z()) << "\"/></joint>\n";
  out.urdf.insert(out.urdf.rfind("</robot>"), gantry.str());
  return out;
}

// The gripper on its gantry, without the grasp fix, raised clear of the ground.
std::unique_ptr<World> raisedGantry(const GantryGripper& g) {
  WorldOptions options;
  options.grasp_fix_enabled = false;
  auto world = std::make_unique<World>(g.urdf, WorldSpec(), options);
  EXPECT_TRUE(world->setJointPositions({"gantry_z_joint"}, {0.5}).ok());
  return world;
}

// grasping.yaml as the setup assistant writes it (the part the simulator reads).
std::string graspingYaml(const GantryGripper& g) {
  std::string links;
  for (const auto& link : g.grasp.finger_links) links += (links.empty() ? "" : ", ") + link;
  return "group: gripper\ngrasp_fix:\n  arm_name: gantry\n  palm_link: " + g.palm + "\n  gripper_links: [" + links +
         "]\n  forces_angle_tolerance: 120\n  update_rate: 5\n  grip_count_threshold: 5\n  max_grip_count: 10\n"
         "  release_tolerance: 0.005\n";
}

enum class Kind { kCube, kCylinder, kSphere };
const char* kindName(Kind kind) {
  return kind == Kind::kCube ? "cube" : kind == Kind::kCylinder ? "cylinder" : "sphere";
}

// An object of width `size` (m) resting on the ground at the origin: a cube, an upright cylinder (as tall as wide
// up to 5 cm) or a sphere.
ObjectSpec object(Kind kind, double size) {
  ObjectSpec spec;
  spec.name = "object";
  double height = size;
  if (kind == Kind::kCube) {
    spec.shape.type = ShapeType::kBox;
    spec.shape.box_size = Eigen::Vector3d::Constant(size);
  } else {
    spec.shape.type = kind == Kind::kSphere ? ShapeType::kSphere : ShapeType::kCylinder;
    spec.shape.radius = size / 2.0;
    spec.shape.length = height = kind == Kind::kSphere ? size : std::min(size, 0.05);
  }
  spec.pose.translation() = Eigen::Vector3d(0, 0, height / 2.0);
  spec.mass = 0.05;
  spec.friction = 0.8;
  return spec;
}

struct Outcome {
  double attach_after = -1.0;   // s from the close command
  double closed_after = -1.0;   // s from the close command until the gripper controller ended it (-1: not by then)
  bool held = true;             // attached at every step of lift and transport
  double lifted = 0.0;          // m the object rose
  double slip = 0.0;            // m: largest change of the object's position in the TCP frame while carried
  double mimic_gap = 0.0;       // rad or m: largest gap of a mimic joint from its master's share while carried
  double release_after = -1.0;  // s from the open command
  double release_speed = 0.0;   // m/s: the object's largest horizontal speed in the 0.1 s after the release
  double place_error = 0.0;     // m from the place point (xy), 0.1 s after the release
  double rest_height_error = 0.0;
};

// The gantry moves along cosine profiles (position and velocity feed-forward); the gripper controller commands
// the finger every step.
class Rig {
 public:
  Rig(const GantryGripper& g, const ObjectSpec& spec) : g_(g), world_(g.urdf, worldSpec(spec), options(g)),
      gripper_(config(g, world_)) {
    finger_ = world_.jointIndex(g.finger);
    world_.setPreStepCallback([this](double t) { command(t); });
  }

  World& world() { return world_; }
  const GantryGripper& gripper() const { return g_; }

  void teleport(const Eigen::Vector3d& tcp, double finger) {
    EXPECT_TRUE(world_.setJointPositions({"gantry_x_joint", "gantry_y_joint", "gantry_z_joint", g_.finger},
                                         {tcp.x(), tcp.y(), tcp.z(), finger})
                    .ok());
    from_ = to_ = tcp;
    gripper_.hold(finger);
  }
  // Moves the TCP to `to` in `duration` s, calling `each` after every step.
  void move(const Eigen::Vector3d& to, double duration, const std::function<void()>& each = [] {}) {
    from_ = to_;
    to_ = to;
    start_ = world_.simTime();
    duration_ = duration;
    run(duration, each);
  }
  void run(double seconds, const std::function<void()>& each = [] {}) {
    const auto steps = static_cast<std::uint64_t>(std::llround(seconds / world_.timeStep()));
    for (std::uint64_t i = 0; i < steps; ++i) {
      world_.step(1);
      each();
    }
  }
  // A new goal, as the simulator's gripper controller sets it (with the fingers' contacts found afresh).
  void setFinger(double position) {
    EXPECT_TRUE(gripper_.setGoal({position, 0.0}, world_.simTime()).ok());
    EXPECT_TRUE(world_.refreshContacts(g_.finger).ok());
    finished_at_ = -1.0;
  }
  // Sim time at which the gripper controller ended the last goal (reached or stalled), -1 while it is active.
  double finishedAt() const { return finished_at_; }
  bool holding() const { return !world_.attachedObjects().empty(); }
  Eigen::Isometry3d tcp() const { return test::linkPose(world_, g_.palm) * g_.grasp.tcp; }
  // The largest |q_mimic - (multiplier * q_master + offset)| over the mimic joints.
  double mimicGap() const {
    const std::vector<double> q = world_.jointPositions();
    double gap = 0.0;
    for (size_t j = 0; j < world_.joints().size(); ++j) {
      const JointInfo& info = world_.joints()[j];
      if (info.mimic_of.empty()) continue;
      const double share = info.mimic_multiplier * q[world_.jointIndex(info.mimic_of)] + info.mimic_offset;
      gap = std::max(gap, std::abs(q[j] - share));
    }
    return gap;
  }
  Eigen::Vector3d objectPosition() const {
    ObjectState state;
    EXPECT_TRUE(world_.objectState("object", &state).ok());
    return state.spec.pose.translation();
  }
  Eigen::Vector3d objectVelocity() const {
    ObjectState state;
    EXPECT_TRUE(world_.objectState("object", &state).ok());
    return state.twist.linear;
  }

 private:
  static WorldSpec worldSpec(const ObjectSpec& spec) {
    WorldSpec world;
    world.name = "gantry";
    world.ground.z = 0.0;
    world.objects.push_back(spec);
    return world;
  }
  static WorldOptions options(const GantryGripper& g) {
    WorldOptions o;
    o.grasp_fix_config = parseGraspingYaml(graspingYaml(g), "grasping.yaml");
    return o;
  }
  static GripperControllerConfig config(const GantryGripper& g, const World& world) {
    const JointInfo& info = world.joints().at(world.jointIndex(g.finger));
    GripperControllerConfig c;
    c.name = "gripper_controller";
    c.joint = g.finger;
    c.lower = info.lower;
    c.upper = info.upper;
    c.effort_limit = info.max_effort;
    c.allow_stalling = true;
    return c;
  }
  void command(double t) {
    const double s = duration_ > 0.0 ? std::min(1.0, std::max(0.0, (t - start_) / duration_)) : 1.0;
    const Eigen::Vector3d position = from_ + (to_ - from_) * (1.0 - std::cos(M_PI * s)) / 2.0;
    const Eigen::Vector3d velocity = (to_ - from_) * (s < 1.0 ? M_PI / (2.0 * duration_) * std::sin(M_PI * s) : 0.0);
    const char* const names[] = {"gantry_x_joint", "gantry_y_joint", "gantry_z_joint"};
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(world_.setPositionTarget(names[i], position[i], velocity[i]).ok());
    const GripperUpdate u = gripper_.update(t, world_.jointPositions()[finger_]);
    if (u.finished) finished_at_ = t;
    EXPECT_TRUE(world_.setPositionTarget(g_.finger, u.command_position, 0.0, u.command_max_effort).ok());
  }

  const GantryGripper& g_;
  World world_;
  GripperController gripper_;
  int finger_ = -1;
  Eigen::Vector3d from_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d to_ = Eigen::Vector3d::Zero();
  double start_ = 0.0;
  double duration_ = 0.0;
  double finished_at_ = -1.0;
};

// Pick at the origin (TCP at the object's centre, or higher where the fingers would reach the ground), lift 10 cm,
// carry 20 cm along x and 10 cm along y, put down, open, retreat.
Outcome pickAndPlace(const GantryGripper& g, Kind kind, double size) {
  const ObjectSpec spec = object(kind, size);
  Rig rig(g, spec);
  Outcome out;
  const double rest = spec.pose.translation().z();
  // Deep enough for the palm to clear the object's top, high enough for the fingers to clear the ground.
  const double top = 2.0 * rest;
  const double grasp_z = std::max({rest, top - g.grasp.palm_depth + 0.003, g.grasp.reach + 0.003});
  const double open = g.grasp.open.at(g.finger);
  const double closed = g.grasp.closed.at(g.finger);
  rig.teleport(Eigen::Vector3d(0, 0, grasp_z + 0.08), open);
  rig.run(0.2);
  rig.move(Eigen::Vector3d(0, 0, grasp_z), 1.0);
  rig.run(0.2);
  rig.setFinger(closed);
  const double closing = rig.world().simTime();
  for (int i = 0; i < 3000 && !rig.holding(); ++i) rig.run(0.001);
  if (!rig.holding()) return out;
  out.attach_after = rig.world().simTime() - closing;
  const Eigen::Vector3d start = rig.objectPosition();
  const Eigen::Vector3d in_tcp = rig.tcp().inverse() * start;
  const auto carried = [&] {
    out.held = out.held && rig.holding();
    out.slip = std::max(out.slip, (rig.tcp().inverse() * rig.objectPosition() - in_tcp).norm());
    out.mimic_gap = std::max(out.mimic_gap, rig.mimicGap());
  };
  rig.move(Eigen::Vector3d(0, 0, grasp_z + 0.10), 1.0, carried);
  out.lifted = rig.objectPosition().z() - start.z();
  const Eigen::Vector3d place(0.2, -0.1, grasp_z + 0.10);
  rig.move(place, 1.5, carried);
  rig.move(Eigen::Vector3d(place.x(), place.y(), grasp_z + 0.002), 1.0);
  rig.run(0.2);
  if (rig.finishedAt() >= 0.0) out.closed_after = rig.finishedAt() - closing;
  rig.setFinger(open);
  const double opening = rig.world().simTime();
  for (int i = 0; i < 1000 && rig.holding(); ++i) rig.run(0.001);
  if (rig.holding()) return out;
  out.release_after = rig.world().simTime() - opening;
  // Where it was let go (a sphere rolls on from there), then at rest once the gripper is gone.
  rig.run(0.1, [&] { out.release_speed = std::max(out.release_speed, rig.objectVelocity().head<2>().norm()); });
  out.place_error = (rig.objectPosition().head<2>() - place.head<2>()).norm();
  rig.move(Eigen::Vector3d(place.x(), place.y(), grasp_z + 0.08), 0.8);
  rig.run(0.5);
  out.rest_height_error = std::abs(rig.objectPosition().z() - rest);
  if (rig.holding()) out.release_after = -1.0;
  return out;
}

using Case = std::tuple<std::string, Kind, double>;

class FixtureGripper : public ::testing::TestWithParam<Case> {};

TEST_P(FixtureGripper, HoldsThroughLiftAndTransportAndReleasesOnOpening) {
  const auto& [file, kind, size] = GetParam();
  const GantryGripper g = gantryGripper(file);
  const Outcome out = pickAndPlace(g, kind, size);
  std::printf("%s %s %.0f mm: attached after %.3f s, close ended after %.3f s (-1: not by the put-down), slip "
              "%.2f mm and mimic gap %.4f while carried, released after %.3f s at up to %.1f mm/s, placed %.1f mm "
              "off, at rest %.1f mm from its height\n",
              file.c_str(), kindName(kind), size * 1000.0, out.attach_after, out.closed_after, out.slip * 1000.0,
              out.mimic_gap, out.release_after, out.release_speed * 1000.0, out.place_error * 1000.0,
              out.rest_height_error * 1000.0);
  ASSERT_GE(out.attach_after, 0.0) << "never attached";
  EXPECT_LT(out.attach_after, 2.5);
  EXPECT_TRUE(out.held) << "dropped while carried";
  EXPECT_GT(out.lifted, 0.09);
  EXPECT_LT(out.slip, 0.003);
  EXPECT_LT(out.mimic_gap, 1e-3) << "the linkage gave way under the squeeze";
  ASSERT_GE(out.release_after, 0.0) << "not released on opening";
  EXPECT_LT(out.release_after, 0.5);
  // A sphere rolls on from any speed it is let go with (boxes and cylinders land flat).
  if (kind == Kind::kSphere) EXPECT_LT(out.release_speed, 0.01) << "the opening fingers kicked the sphere";
  EXPECT_LT(out.place_error, 0.015);
  EXPECT_LT(out.rest_height_error, 0.005);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, FixtureGripper,
    ::testing::Combine(::testing::Values("parallel_hand.urdf", "jaw_gripper.urdf", "adaptive_gripper.urdf"),
                       ::testing::Values(Kind::kCube, Kind::kCylinder, Kind::kSphere), ::testing::Values(0.03, 0.06)),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string name = std::get<0>(info.param);
      name = name.substr(0, name.find('.'));
      return name + "_" + kindName(std::get<1>(info.param)) + "_" +
             std::to_string(static_cast<int>(std::lround(std::get<2>(info.param) * 1000.0))) + "mm";
    });

TEST(FixtureGripper, TheAdaptiveGrippersMimicJointWithDisagreeingLimitsFollowsItsMaster) {
  const GantryGripper g = gantryGripper("adaptive_gripper.urdf");
  const std::unique_ptr<World> raised = raisedGantry(g);
  World& world = *raised;
  ASSERT_TRUE(world.setPositionTarget("finger_joint", 0.6).ok());
  world.step(1500);
  const std::vector<double> q = world.jointPositions();
  EXPECT_NEAR(q[world.jointIndex("finger_joint")], 0.6, 0.01);
  // Its own limits are [0, 0.8757]; its master makes it -0.6.
  EXPECT_NEAR(q[world.jointIndex("left_inner_finger_joint")], -0.6, 0.01);
}

// A jump of its command (open, close) ramps at the master's URDF velocity limit, as a gripper's motor moves.
TEST(FixtureGripper, TheAdaptiveGrippersLinkageStaysWithinItsMastersLimitsAndSpeed) {
  const GantryGripper g = gantryGripper("adaptive_gripper.urdf");
  const std::unique_ptr<World> raised = raisedGantry(g);
  World& world = *raised;
  const int finger = world.jointIndex("finger_joint");
  const JointInfo& info = world.joints()[static_cast<size_t>(finger)];
  double lowest = 1e9, highest = -1e9;
  for (const double target : {info.upper, info.lower, info.upper}) {
    const double travel = std::abs(target - world.jointPositions()[static_cast<size_t>(finger)]);
    ASSERT_TRUE(world.setPositionTarget("finger_joint", target).ok());
    double reached = -1.0;  // s until within 0.01 of the target
    for (int i = 0; i < 1500; ++i) {
      world.step(1);
      const double q = world.jointPositions()[static_cast<size_t>(finger)];
      lowest = std::min(lowest, q);
      highest = std::max(highest, q);
      if (reached < 0.0 && std::abs(q - target) < 0.01) reached = (i + 1) * world.timeStep();
    }
    std::printf("finger_joint to %.3f: %.3f travelled in %.3f s, limit %.3f rad/s\n", target, travel, reached,
                info.max_velocity);
    ASSERT_GE(reached, 0.0) << "never reached " << target;
    EXPECT_GE(reached, 0.95 * (travel - 0.01) / info.max_velocity);
  }
  std::printf("finger_joint within [%.4f, %.4f], limits [%.4f, %.4f]\n", lowest, highest, info.lower, info.upper);
  EXPECT_GE(lowest, info.lower - 0.01);
  EXPECT_LE(highest, info.upper + 0.01);
}

// Squeezing an object, then closing on nothing when it goes (deleted, as bench-pick's cleanup does): the exact
// coupling after the solve must not carry the master past its limit (it reached 1.9 rad of [0, 0.8]).
TEST(FixtureGripper, TheAdaptiveGrippersMasterStaysWithinItsLimitsWhenASqueezedObjectGoes) {
  const GantryGripper g = gantryGripper("adaptive_gripper.urdf");
  const ObjectSpec spec = object(Kind::kSphere, 0.06);
  Rig rig(g, spec);
  const double rest = spec.pose.translation().z();
  const double grasp_z = std::max({rest, 2.0 * rest - g.grasp.palm_depth + 0.003, g.grasp.reach + 0.003});
  rig.teleport(Eigen::Vector3d(0, 0, grasp_z), g.grasp.open.at(g.finger));
  rig.run(0.2);
  rig.setFinger(g.grasp.closed.at(g.finger));
  rig.run(1.0);
  const int finger = rig.world().jointIndex(g.finger);
  const JointInfo& info = rig.world().joints()[static_cast<size_t>(finger)];
  const double squeezed = rig.world().jointPositions()[static_cast<size_t>(finger)];
  ASSERT_TRUE(rig.world().deleteObject("object").ok());
  double lowest = 1e9, highest = -1e9;
  const auto track = [&] {
    const double q = rig.world().jointPositions()[static_cast<size_t>(finger)];
    lowest = std::min(lowest, q);
    highest = std::max(highest, q);
  };
  rig.move(Eigen::Vector3d(0, 0, grasp_z - 0.04), 0.3, track);
  rig.run(1.0, track);
  std::printf("finger_joint %.4f on the object, then within [%.4f, %.4f], limits [%.4f, %.4f], mimic gap %.5f\n",
              squeezed, lowest, highest, info.lower, info.upper, rig.mimicGap());
  EXPECT_GE(lowest, info.lower - 0.01);
  EXPECT_LE(highest, info.upper + 0.01);
  EXPECT_LT(rig.mimicGap(), 1e-3);
}

// World::refreshContacts (the simulator's gripper controller calls it on each new goal): the contact points between
// the fingers and the object they hold are gone until the next step, which finds them again from the poses, each
// normal pushing its finger away from the object's centre; the object's other contacts (the ground) stay. A normal
// kept from the closing (Bullet keeps points while the bodies stay close, and the grasp fix keeps them close) once
// held a hand's fingers shut against their opening effort (bench-pick, seven_dof_hand: 1 open in about 150).
TEST(FixtureGripper, ARefreshFindsTheFingersContactsWithAHeldObjectAfresh) {
  const GantryGripper g = gantryGripper("parallel_hand.urdf");
  const ObjectSpec spec = object(Kind::kCube, 0.03);
  Rig rig(g, spec);
  const double grasp_z = std::max(spec.pose.translation().z(), g.grasp.reach + 0.003);
  rig.teleport(Eigen::Vector3d(0, 0, grasp_z), g.grasp.open.at(g.finger));
  rig.run(0.2);
  rig.setFinger(g.grasp.closed.at(g.finger));
  for (int i = 0; i < 3000 && !rig.holding(); ++i) rig.run(0.001);
  ASSERT_TRUE(rig.holding()) << "never attached";
  rig.run(0.2);
  const auto fingers = [&](const World& world, int* others) {
    int count = 0;
    *others = 0;
    for (const Contact& c : world.contacts()) {
      const bool finger_a = std::count(g.grasp.finger_links.begin(), g.grasp.finger_links.end(), c.body_a) > 0;
      const bool finger_b = std::count(g.grasp.finger_links.begin(), g.grasp.finger_links.end(), c.body_b) > 0;
      if ((finger_a && c.body_b == "object") || (finger_b && c.body_a == "object")) {
        ++count;
        // normal_on_b points from b to a: from the object towards the finger when the finger is a.
        const Eigen::Vector3d towards_finger = finger_a ? c.normal_on_b : Eigen::Vector3d(-c.normal_on_b);
        const Eigen::Vector3d outwards = c.position_on_b - rig.objectPosition();
        EXPECT_GT(towards_finger.dot(outwards), 0.0) << "a normal pushing " << (finger_a ? c.body_a : c.body_b)
                                                     << " into the object: " << towards_finger.transpose();
      } else {
        ++*others;
      }
    }
    return count;
  };
  int others_before = 0, others = 0;
  ASSERT_GT(fingers(rig.world(), &others_before), 0);
  EXPECT_GT(others_before, 0) << "the cube on the ground";
  ASSERT_TRUE(rig.world().refreshContacts(g.finger).ok());
  EXPECT_EQ(fingers(rig.world(), &others), 0);
  EXPECT_EQ(others, others_before);
  rig.run(0.001);
  EXPECT_GT(fingers(rig.world(), &others), 0);
  EXPECT_TRUE(rig.holding());
  const Result unknown = rig.world().refreshContacts("no_such_joint");
  EXPECT_EQ(unknown.status, Status::kUnknownJoint);
  EXPECT_NE(unknown.message.find("no_such_joint"), std::string::npos) << unknown.message;
}

// The jaw gripper closing on an upright 3 cm x 6 cm cylinder, squeezed from its middle: held with opposed, level
// forces and attached. With the solver stopped unconverged (20 iterations) the jaws chattered and their friction
// wedged it into the ground (jaw forces 110 deg apart, 48-60 N down each, the ground pushing 114 N): never attached.
TEST(FixtureGripper, TheJawGripperHoldsAnUprightCylinderWithLevelForces) {
  const GantryGripper g = gantryGripper("jaw_gripper.urdf");
  ObjectSpec spec = object(Kind::kCylinder, 0.03);
  spec.shape.length = 0.06;
  spec.pose.translation().z() = 0.03;
  spec.mass = 0.1;
  Rig rig(g, spec);
  rig.teleport(Eigen::Vector3d(0, 0, 0.11), g.grasp.open.at(g.finger));
  rig.run(0.2);
  rig.move(Eigen::Vector3d(0, 0, 0.03), 1.0);
  rig.run(0.2);
  rig.setFinger(g.grasp.closed.at(g.finger));
  const double closing = rig.world().simTime();
  double ground = 0.0;  // N: the ground's largest push on the cylinder before it was attached
  for (int i = 0; i < 2500 && !rig.holding(); ++i) {
    rig.run(0.001);
    double push = 0.0;
    for (const Contact& c : rig.world().contacts()) {
      if ((c.body_a == "ground" && c.body_b == "object") || (c.body_a == "object" && c.body_b == "ground")) {
        push += c.normal_impulse / rig.world().timeStep();
      }
    }
    ground = std::max(ground, push);
  }
  const double weight = spec.mass * 9.81;
  std::printf("%s after %.3f s; the ground pushed up to %.2f N on the %.2f N cylinder\n",
              rig.holding() ? "attached" : "not attached", rig.world().simTime() - closing, ground, weight);
  EXPECT_TRUE(rig.holding()) << "never attached";
  EXPECT_LT(ground, weight + 5.0) << "the jaws pressed the cylinder into the ground";
}

}  // namespace
}  // namespace sixdof_sim
