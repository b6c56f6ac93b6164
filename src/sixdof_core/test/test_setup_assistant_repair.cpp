// The setup assistant's repairs: computed inertias and the TCP frame written into the URDF, mimic joints whose
// limits disagree with their master (a warning, never an error), and the repair mode's command line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sixdof_core/setup_assistant.h"

namespace sixdof_core {
namespace {

std::string adaptiveGripper() {
  return readTextFile(std::string(SIXDOF_TEST_ROBOTS_DIR) + "/urdf/adaptive_gripper.urdf");
}

GripperQuery adaptiveQuery() {
  GripperQuery query;
  query.parent_link = "gripper_base";
  query.joints = {"finger_joint", "right_outer_knuckle_joint", "left_inner_knuckle_joint",
                  "right_inner_knuckle_joint", "left_inner_finger_joint", "right_inner_finger_joint"};
  return query;
}

TEST(SetupAssistantRepair, InertiasAndTheTcpFrameGoIntoTheUrdf) {
  RepairOptions options;
  options.gripper = adaptiveQuery();
  const RepairResult result = repairModel(adaptiveGripper(), options);
  ASSERT_EQ(result.inertias.size(), 6u);
  EXPECT_EQ(result.tcp_frame_added, "tcp");
  ASSERT_TRUE(result.grasp.has_value());
  const RobotModel repaired(result.urdf, "");
  for (const InertiaRepair& repair : result.inertias) {
    EXPECT_EQ(inertialProblem(repaired.link(repair.link).inertial), "") << repair.link;
    EXPECT_NEAR(repaired.link(repair.link).inertial->mass, repair.inertial.mass, 1e-9 * repair.inertial.mass);
  }
  RobotState state(std::make_shared<const RobotModel>(result.urdf, ""));
  EXPECT_TRUE((state.linkTransform("gripper_base").inverse() * state.linkTransform("tcp")).isApprox(result.grasp->tcp,
                                                                                                     1e-8));
  const std::string yaml = describeRepairs(result);
  EXPECT_NE(yaml.find("- {link: \"left_inner_finger\", problem: \"no <inertial>\", source: collision"),
            std::string::npos) << yaml;
  EXPECT_NE(yaml.find("tcp_frame_added: \"tcp\""), std::string::npos);
  EXPECT_NE(yaml.find("pad_links: [\"right_inner_finger\", \"left_inner_finger\"]"), std::string::npos);
  // Without a gripper and with nothing to repair, the text stays as it is.
  const std::string arm = readTextFile(std::string(SIXDOF_TEST_ROBOTS_DIR) + "/urdf/parallel_hand.urdf");
  const RepairResult untouched = repairModel(arm, RepairOptions());
  EXPECT_EQ(untouched.urdf, arm);
  EXPECT_NE(describeRepairs(untouched).find("inertias: []"), std::string::npos);
}

TEST(SetupAssistantRepair, AMimicJointsOwnLimitsAreAWarningNotAnError) {
  const RobotModel model(adaptiveGripper(), "");
  const std::vector<MimicLimitConflict> conflicts = mimicLimitConflicts(model);
  ASSERT_EQ(conflicts.size(), 1u);
  EXPECT_EQ(conflicts[0].joint, "left_inner_finger_joint");
  EXPECT_EQ(conflicts[0].master, "finger_joint");
  EXPECT_DOUBLE_EQ(conflicts[0].from, -0.8);
  EXPECT_DOUBLE_EQ(conflicts[0].to, 0.0);
  EXPECT_NE(describeModel(model).find("mimic_limit_conflicts:\n- {joint: \"left_inner_finger_joint\""),
            std::string::npos);
  // A state naming the mimic joint at a value outside its own limits loads (MoveIt's rule).
  const std::string srdf = R"(<robot name="adaptive_gripper"><group name="g"><joint name="finger_joint"/>
      <joint name="left_inner_finger_joint"/></group><group_state name="closed" group="g">
      <joint name="finger_joint" value="0.8"/><joint name="left_inner_finger_joint" value="-0.8"/></group_state>
      </robot>)";
  EXPECT_NO_THROW(RobotModel(adaptiveGripper(), srdf));
}

TEST(SetupAssistantRepair, CommandLine) {
  const SetupAssistantCommand c = parseSetupAssistantArguments(
      {"--urdf", "in.urdf", "--urdf-out", "out.urdf", "--repairs", "r.yaml", "--inertia-density", "2500",
       "--gripper-parent", "tool0", "--gripper-joint", "a", "--gripper-joint", "b", "--pad-link", "pa", "--pad-link",
       "pb", "--open", "a=0.1", "--closed", "a=-0.2", "--closing-direction", "0 1 0", "--tcp", "0 0 0.1 0 0 1.5",
       "--tcp-parent", "flange"});
  EXPECT_EQ(c.urdf_out_path, "out.urdf");
  EXPECT_EQ(c.repairs_path, "r.yaml");
  EXPECT_EQ(c.repair.density, 2500.0);
  ASSERT_TRUE(c.repair.gripper.has_value());
  EXPECT_EQ(c.repair.gripper->joints, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(c.repair.gripper->pad_links, (std::vector<std::string>{"pa", "pb"}));
  EXPECT_EQ(c.repair.gripper->open.at("a"), 0.1);
  EXPECT_EQ(c.repair.gripper->closed.at("a"), -0.2);
  EXPECT_TRUE(c.repair.gripper->tcp->translation().isApprox(Eigen::Vector3d(0, 0, 0.1)));
  EXPECT_EQ(c.repair.gripper->tcp_parent, "flange");
  const auto error = [](const std::vector<std::string>& args) {
    try {
      parseSetupAssistantArguments(args);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error({"--urdf", "x", "--urdf-out", "y"}).find("go together"), std::string::npos);
  EXPECT_NE(error({"--urdf", "x", "--urdf-out", "y", "--repairs", "z", "--gripper-joint", "a"}).find("parent"),
            std::string::npos);
  EXPECT_NE(error({"--urdf", "x", "--urdf-out", "y", "--repairs", "z", "--gripper-parent", "p", "--gripper-joint", "a",
                   "--tcp", "1 2 3"}).find("6 numbers"), std::string::npos);
  EXPECT_NE(error({"--urdf", "x", "--urdf-out", "y", "--repairs", "z", "--inertia-density", "0"}).find("> 0"),
            std::string::npos);
  EXPECT_NE(error({"--urdf", "x", "--describe", "d", "--inertia-density", "5"}).find("--urdf-out mode"),
            std::string::npos);
  EXPECT_NE(error({"--urdf", "x", "--urdf-out", "y", "--repairs", "z", "--srdf-out", "s"}).find("cannot be combined"),
            std::string::npos);
}

}  // namespace
}  // namespace sixdof_core
