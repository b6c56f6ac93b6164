// The grasp fix configured from a config package's grasping.yaml, and the URDF's gazebo_grasp_fix block winning
// over it.

#include <gtest/gtest.h>

#include "test_helpers.h"

namespace sixdof_sim {
namespace {

const char* const kGrasping = R"(group: gripper
tcp: {frame: tcp, parent_link: link_6, xyz: [0.13, 0, 0], rpy: [0, 1.57, 0]}
grasp_fix:
  arm_name: arm
  palm_link: link_6
  gripper_links: [left_pad, right_pad]
  forces_angle_tolerance: 110.0
  max_grip_count: 6
  disable_collisions_on_attach: true
)";

TEST(GraspingYaml, ReadsTheGraspFixWithThePluginsDefaults) {
  const GraspFixConfig c = parseGraspingYaml(kGrasping, "grasping.yaml");
  EXPECT_EQ(c.arm_name, "arm");
  EXPECT_EQ(c.palm_link, "link_6");
  EXPECT_EQ(c.gripper_links, (std::vector<std::string>{"left_pad", "right_pad"}));
  EXPECT_DOUBLE_EQ(c.forces_angle_tolerance, 110.0);
  EXPECT_DOUBLE_EQ(c.update_rate, 5.0);    // gazebo_grasp_fix's default
  EXPECT_EQ(c.max_grip_count, 6);
  EXPECT_EQ(c.grip_count_threshold, 3);    // max_grip_count / 2, as the plugin
  EXPECT_DOUBLE_EQ(c.release_tolerance, 0.005);
  EXPECT_TRUE(c.disable_collisions_on_attach);
}

TEST(GraspingYaml, BadInputNamesTheKey) {
  const auto error = [](const std::string& text) {
    return test::errorMessage<std::invalid_argument>([&] { parseGraspingYaml(text, "my/grasping.yaml"); });
  };
  EXPECT_NE(error("tcp: {}\n").find("no 'grasp_fix' mapping"), std::string::npos);
  EXPECT_NE(error("grasp_fix: [\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(error("grasp_fix: {palm_link: p, gripper_links: [f], fingers: 2}\n").find("'grasp_fix.fingers'"),
            std::string::npos);
  EXPECT_NE(error("grasp_fix: {palm_link: p, gripper_links: [f], update_rate: fast}\n").find("update_rate"),
            std::string::npos);
  EXPECT_NE(error("grasp_fix: {palm_link: p, gripper_links: f}\n").find("gripper_links"), std::string::npos);
  EXPECT_NE(error("grasp_fix: {gripper_links: [f]}\n").find("palm_link"), std::string::npos);
  const std::string angle = error("grasp_fix: {palm_link: p, gripper_links: [f], forces_angle_tolerance: 45}\n");
  EXPECT_NE(angle.find("my/grasping.yaml"), std::string::npos) << angle;
  EXPECT_NE(angle.find("forces_angle_tolerance"), std::string::npos) << angle;
}

TEST(GraspingYaml, TheUrdfBlockWinsOverIt) {
  WorldOptions options = test::options(true);
  options.grasp_fix_config = parseGraspingYaml(
      "grasp_fix: {palm_link: palm, gripper_links: [finger1], update_rate: 50}\n", "grasping.yaml");
  World world(test::robotUrdf(), WorldSpec(), options);
  ASSERT_TRUE(world.graspFixConfig().has_value());
  EXPECT_EQ(world.graspFixConfig()->palm_link, test::graspConfig().palm_link);
  EXPECT_DOUBLE_EQ(world.graspFixConfig()->update_rate, test::graspConfig().update_rate);
  // Without a block the options are the configuration.
  const std::string plain = "<robot name='r'><link name='a'/><joint name='j' type='prismatic'><parent link='a'/>"
                            "<child link='b'/><axis xyz='0 1 0'/><limit lower='0' upper='1' effort='1' velocity='1'/>"
                            "</joint><link name='b'><inertial><mass value='1'/><inertia ixx='1' iyy='1' izz='1' "
                            "ixy='0' ixz='0' iyz='0'/></inertial></link></robot>";
  options.grasp_fix_config = parseGraspingYaml("grasp_fix: {palm_link: a, gripper_links: [b]}\n", "grasping.yaml");
  World own(plain, WorldSpec(), options);
  ASSERT_TRUE(own.graspFixConfig().has_value());
  EXPECT_EQ(own.graspFixConfig()->palm_link, "a");
}

}  // namespace
}  // namespace sixdof_sim
