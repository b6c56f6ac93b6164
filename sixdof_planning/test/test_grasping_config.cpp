// move_group's grasping information (robot_description_grasping): the sixdof arm's grasping.yaml read against its
// model and served as get_robot_model's gripper, and every kind of text that does not fit the model refused with
// the key named.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <sixdof_core/robot_model.h>

#include "sixdof_planning/config.h"
#include "sixdof_planning/conversions.h"
#include "sixdof_planning/grasping_config.h"
#include "sixdof_planning/query_robot_model_service_capability.h"

namespace sixdof_planning {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const sixdof_core::RobotModel& model() {
  static const sixdof_core::RobotModel robot(
      readFile(SIXDOF_DESCRIPTION_DIR "/urdf/sixdof.urdf"), readFile(SIXDOF_DESCRIPTION_DIR "/config/sixdof.srdf"),
      sixdof_core::PackageResolver::fromMap({{"sixdof_description", SIXDOF_DESCRIPTION_DIR}}));
  return robot;
}

// A grasping.yaml of the sixdof arm in the setup assistant's layout (its grasp_fix is the simulator's).
const char* const kGrasping = R"(group: gripper
end_effector: hand
tcp: {frame: tcp, parent_link: link6, xyz: [0.0, 0.0, 0.113], rpy: [0.0, 0.0, 0.0], source: link 'tcp'}
open: {state: open, positions: {finger1_joint: 0.04}}
closed: {state: close, positions: {finger1_joint: 0.0}}
max_opening: 0.08
closed_width: 0.0
finger_reach: 0.015
palm_depth: 0.053
pad_links: [finger2, finger1]
closing_direction: [0.0, 1.0, 0.0]
approach_direction: [0.0, 0.0, 2.0]
grasp_fix: {palm_link: link6, gripper_links: [finger1, finger2]}
)";

std::string errorOf(const std::string& text) {
  try {
    parseGraspingConfig(text, model(), "robot_description_grasping");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// kGrasping with the first occurrence of `from` replaced by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = kGrasping;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(GraspingConfig, TheSixdofArmsPackageFileIsReadAgainstItsModel) {
  const GraspingConfig c =
      parseGraspingConfig(readFile(SIXDOF_DESCRIPTION_DIR "/config/grasping.yaml"), model(), "grasping.yaml");
  EXPECT_EQ(c.group, "gripper");
  EXPECT_EQ(c.end_effector, "hand");
  EXPECT_EQ(c.tcp_frame, "tcp");
  EXPECT_EQ(c.parent_link, "link6");
  EXPECT_TRUE(c.tcp.translation().isApprox(Eigen::Vector3d(0, 0, 0.113), 1e-12));
  EXPECT_EQ(c.open.name, "open");
  EXPECT_DOUBLE_EQ(c.open.positions.at("finger1_joint"), 0.04);
  EXPECT_EQ(c.closed.name, "close");
  EXPECT_DOUBLE_EQ(c.closed.positions.at("finger1_joint"), 0.0);
  EXPECT_EQ(c.closed.positions.size(), 1u);  // the mimic finger2_joint follows
  EXPECT_DOUBLE_EQ(c.max_opening, 0.08);
  EXPECT_GT(c.finger_reach, 0.0);
  EXPECT_GT(c.palm_depth, c.finger_reach);
  EXPECT_EQ(c.pad_links.size(), 2u);
  EXPECT_TRUE(c.closing_direction.isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(c.approach_direction.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(GraspingConfig, GetRobotModelServesItAsTheGripper) {
  const GraspingConfig c = parseGraspingConfig(kGrasping, model(), "grasping");
  const sixdof_msgs::RobotModelGripper msg = describeGripper(c);
  EXPECT_EQ(msg.group, "gripper");
  EXPECT_EQ(msg.end_effector, "hand");
  EXPECT_EQ(msg.tcp_frame, "tcp");
  EXPECT_EQ(msg.parent_link, "link6");
  EXPECT_TRUE(poseToEigen(msg.tcp).isApprox(c.tcp, 1e-12));
  EXPECT_EQ(msg.open.group, "gripper");
  EXPECT_EQ(msg.open.name, "open");
  EXPECT_EQ(msg.open.joint_names, std::vector<std::string>{"finger1_joint"});
  EXPECT_EQ(msg.closed.positions, std::vector<double>{0.0});
  EXPECT_DOUBLE_EQ(msg.max_opening, 0.08);
  EXPECT_DOUBLE_EQ(msg.palm_depth, 0.053);
  EXPECT_EQ(msg.pad_links, (std::vector<std::string>{"finger2", "finger1"}));
  EXPECT_DOUBLE_EQ(msg.approach_direction.z, 1.0);  // normalized
  // Without a palm depth there is no palm across the pads.
  const GraspingConfig open_palm = parseGraspingConfig(edited("palm_depth: 0.053\n", ""), model(), "grasping");
  EXPECT_TRUE(std::isinf(open_palm.palm_depth));
}

TEST(GraspingConfig, TextThatDoesNotFitTheModelNamesTheKey) {
  const auto expect = [](const std::string& text, const std::string& part) {
    const std::string error = errorOf(text);
    EXPECT_NE(error.find("robot_description_grasping"), std::string::npos) << error;
    EXPECT_NE(error.find(part), std::string::npos) << "expected '" << part << "' in: " << error;
  };
  expect("group: [\n", "not valid YAML");
  expect("- a\n", "must be a YAML mapping");
  expect(edited("max_opening:", "fingers: 2\nmax_opening:"), "'fingers' is not a key");
  expect(edited("source: link 'tcp'", "colour: red"), "'tcp.colour' is not a key");
  expect(edited("group: gripper", "group: hand"), "'group' names group 'hand'");
  expect(edited("group: gripper", "group: arm"), "no SRDF end effector of group 'arm'");
  expect(edited("end_effector: hand", "end_effector: paw"), "named 'paw'");
  expect(edited("parent_link: link6", "parent_link: link9"), "'tcp.parent_link' names link 'link9'");
  expect(edited("parent_link: link6", "parent_link: link5"), "not the parent link 'link6'");
  expect(edited("xyz: [0.0, 0.0, 0.113]", "xyz: [0.0, 0.0]"), "'tcp.xyz' must be a list of 3 numbers");
  expect(edited("xyz: [0.0, 0.0, 0.113]", "xyz: [0.0, 0.0, 0.12]"), "'tcp.frame' is the URDF's link 'tcp'");
  expect(edited("finger1_joint: 0.04", "finger2_joint: 0.04"), "'open.positions.finger2_joint' is not an actuated");
  expect(edited("finger1_joint: 0.04", "finger1_joint: 0.05"), "outside the joint's limits");
  expect(edited("finger1_joint: 0.04", "finger1_joint: 0.03"), "disagrees with the SRDF's state 'open'");
  expect(edited("{finger1_joint: 0.0}", "{}"), "'closed.positions' has no position of joint 'finger1_joint'");
  expect(edited("closed: {state: close, positions: {finger1_joint: 0.0}}\n", ""), "'closed' is missing");
  expect(edited("max_opening: 0.08", "max_opening: 0"), "'max_opening' must be a finite number > 0");
  expect(edited("finger_reach: 0.015", "finger_reach: wide"), "'finger_reach' must be a number");
  expect(edited("palm_depth: 0.053", "palm_depth: -1"), "'palm_depth' must be > 0");
  expect(edited("pad_links: [finger2, finger1]", "pad_links: [finger2]"), "'pad_links' must be a list of two");
  expect(edited("pad_links: [finger2, finger1]", "pad_links: [finger2, claw]"), "names link 'claw'");
  expect(edited("closing_direction: [0.0, 1.0, 0.0]", "closing_direction: [0, 0, 0]"),
         "'closing_direction' must not be zero");
}

// The sixdof arm's suction variant (sixdof_description's `tool: suction`): a `suction` mapping instead of fingers.
TEST(GraspingConfig, ASuctionToolIsServedWithItsCupAndVacuum) {
  const sixdof_core::RobotModel suction_model(
      readFile(SIXDOF_DESCRIPTION_DIR "/urdf/sixdof_suction.urdf"),
      readFile(SIXDOF_DESCRIPTION_DIR "/config/suction/sixdof_suction.srdf"),
      sixdof_core::PackageResolver::fromMap({{"sixdof_description", SIXDOF_DESCRIPTION_DIR}}));
  const std::string text = readFile(SIXDOF_DESCRIPTION_DIR "/config/suction/grasping.yaml");
  const GraspingConfig c = parseGraspingConfig(text, suction_model, "grasping.yaml");
  EXPECT_EQ(c.suction_cup, "tcp");
  EXPECT_EQ(c.vacuum_controller, "gripper_controller");
  EXPECT_DOUBLE_EQ(c.max_payload, 0.5);
  EXPECT_EQ(c.parent_link, "link6");
  const sixdof_msgs::RobotModelGripper msg = describeGripper(c);
  EXPECT_EQ(msg.suction_cup, "tcp");
  EXPECT_EQ(msg.vacuum_controller, "gripper_controller");
  EXPECT_TRUE(msg.open.joint_names.empty());
  // The fingered gripper's keys are not needed; a suction mapping without its cup, or naming no link, is refused.
  const auto error = [&](const std::string& from, const std::string& to) {
    std::string bad = text;
    bad.replace(bad.find(from), from.size(), to);
    try {
      parseGraspingConfig(bad, suction_model, "grasping");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("cup_link: tcp", "cup_link: nozzle").find("'suction.cup_link' names link 'nozzle'"),
            std::string::npos);
  EXPECT_NE(error("cup_link: tcp,", "").find("'suction.cup_link' is missing"), std::string::npos);
  EXPECT_NE(error("max_payload: 0.5", "max_payload: -1").find("'suction.max_payload' must be a finite number > 0"),
            std::string::npos);
  EXPECT_NE(error("max_payload: 0.5", "suction_force: 3").find("'suction.suction_force' is not a key"),
            std::string::npos);
}

}  // namespace
}  // namespace sixdof_planning
