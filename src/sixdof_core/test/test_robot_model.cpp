#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "sixdof_core/robot_model.h"
#include "test_models.h"

namespace sixdof_core {
namespace {

// Expects constructing the arm model with `srdf` to throw a RobotModelError mentioning `needle`.
void expectModelError(const std::string& urdf, const std::string& srdf, const std::string& needle) {
  try {
    RobotModel model(urdf, srdf, armResolver());
    ADD_FAILURE() << "no error for URDF/SRDF:\n" << urdf << "\n" << srdf;
  } catch (const RobotModelError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << "message: " << e.what();
  }
}

void expectSrdfError(const std::string& srdf, const std::string& needle) {
  expectModelError(readTextFile(armUrdf()), srdf, needle);
}

std::string srdfWith(const std::string& body) { return "<robot name=\"sixdof\">" + body + "</robot>"; }

TEST(RobotModel, ArmJointsLinksAndVariables) {
  const auto model = armModel();
  EXPECT_EQ(model->name(), "sixdof");
  EXPECT_EQ(model->rootLink(), "base_link");
  EXPECT_EQ(model->joints().size(), 10u);
  EXPECT_EQ(model->links().size(), 11u);
  const std::vector<std::string> variables{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "finger1_joint"};
  EXPECT_EQ(model->variableNames(), variables);

  // Limits from the joint table in docs/design.md.
  const JointModel& joint2 = model->joint("joint2");
  EXPECT_EQ(joint2.type, JointType::kRevolute);
  EXPECT_EQ(joint2.parent_link, "link1");
  EXPECT_EQ(joint2.child_link, "link2");
  EXPECT_TRUE(joint2.axis.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_DOUBLE_EQ(joint2.limits.lower, -1.92);
  EXPECT_DOUBLE_EQ(joint2.limits.upper, 1.92);
  EXPECT_GT(joint2.limits.velocity, 0.0);
  EXPECT_GT(joint2.limits.effort, 0.0);
  EXPECT_FALSE(joint2.isMultiTurn());
  EXPECT_TRUE(model->joint("joint6").isMultiTurn());
  EXPECT_EQ(model->joint("palm_joint").type, JointType::kFixed);
  EXPECT_FALSE(model->joint("palm_joint").isActive());

  const JointModel& finger2 = model->joint("finger2_joint");
  EXPECT_EQ(finger2.type, JointType::kPrismatic);
  ASSERT_TRUE(finger2.mimic.has_value());
  EXPECT_EQ(finger2.mimic->joint, "finger1_joint");
  EXPECT_DOUBLE_EQ(finger2.mimic->multiplier, 1.0);
  EXPECT_FALSE(finger2.isActive());

  // Topological order: every link's parent comes first.
  for (size_t l = 1; l < model->links().size(); ++l) EXPECT_LT(model->links()[l].parent_link, static_cast<int>(l));
  const LinkModel& palm = model->link("palm");
  EXPECT_EQ(model->links()[palm.parent_link].name, "link6");
  EXPECT_EQ(model->links()[model->link("finger1").parent_link].name, "palm");
  EXPECT_EQ(model->links()[model->link("finger2").parent_link].name, "palm");
  EXPECT_EQ(model->linkIndex("nope"), -1);
  EXPECT_THROW(model->joint("nope"), std::out_of_range);
  EXPECT_EQ(model->chainJoints("base_link", "link6").size(), 6u);
  EXPECT_THROW(model->chainJoints("link6", "base_link"), RobotModelError);
}

TEST(RobotModel, ArmSemantics) {
  const auto model = armModel();
  ASSERT_EQ(model->groups().size(), 3u);
  const JointGroup* arm = model->findGroup("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_TRUE(arm->isChain());
  EXPECT_EQ(arm->chain_base, "base_link");
  EXPECT_EQ(arm->chain_tip, "link6");
  EXPECT_EQ(arm->active_joints, (std::vector<std::string>{"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"}));
  const JointGroup* gripper = model->findGroup("gripper");
  ASSERT_NE(gripper, nullptr);
  EXPECT_EQ(gripper->joints, (std::vector<std::string>{"finger1_joint", "finger2_joint"}));
  EXPECT_EQ(gripper->active_joints, (std::vector<std::string>{"finger1_joint"}));
  const JointGroup* both = model->findGroup("arm_with_gripper");
  ASSERT_NE(both, nullptr);
  EXPECT_EQ(both->subgroups, (std::vector<std::string>{"arm", "gripper"}));
  EXPECT_EQ(both->active_joints.size(), 7u);
  EXPECT_EQ(model->findGroup("nope"), nullptr);

  EXPECT_EQ(model->groupStates().size(), 3u);
  const GroupState* open = model->findGroupState("gripper", "open");
  ASSERT_NE(open, nullptr);
  EXPECT_DOUBLE_EQ(open->values.at("finger1_joint"), 0.04);
  EXPECT_NE(model->findGroupState("arm", "home pose"), nullptr);
  EXPECT_EQ(model->findGroupState("arm", "open"), nullptr);

  ASSERT_EQ(model->endEffectors().size(), 1u);
  EXPECT_EQ(model->endEffectors()[0].name, "hand");
  EXPECT_EQ(model->endEffectors()[0].parent_link, "link6");
  EXPECT_EQ(model->endEffectors()[0].group, "gripper");
  EXPECT_EQ(model->endEffectors()[0].parent_group, "arm");
  ASSERT_EQ(model->virtualJoints().size(), 1u);
  EXPECT_EQ(model->virtualJoints()[0].parent_frame, "world");
  EXPECT_EQ(model->virtualJoints()[0].type, "fixed");

  const auto& pairs = model->disabledCollisionPairs();
  EXPECT_EQ(pairs.size(), 10u);
  EXPECT_EQ(pairs.back().link1, "finger1");
  EXPECT_EQ(pairs.back().link2, "finger2");
  EXPECT_EQ(pairs.back().reason, "Never");
}

TEST(RobotModel, CollisionGeometry) {
  const auto arm = armModel();
  const auto arm_geometry = arm->collisionGeometry();
  EXPECT_EQ(arm_geometry.size(), arm->links().size() - 1);  // every link but tcp
  EXPECT_TRUE(arm->link("tcp").collision.shapes.empty());
  for (const auto& link : arm_geometry) EXPECT_FALSE(link.shapes.empty()) << link.link_name;

  // The fixture's primitives, as written in test/data/ur_like.urdf.
  const auto model = RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf", testResolver());
  const LinkModel& base = model->link("base_link");
  ASSERT_EQ(base.collision.shapes.size(), 1u);
  EXPECT_EQ(base.collision.link_name, "base_link");
  EXPECT_EQ(base.collision.shapes[0].shape.type, Shape::Type::kCylinder);
  EXPECT_DOUBLE_EQ(base.collision.shapes[0].shape.radius, 0.075);
  EXPECT_DOUBLE_EQ(base.collision.shapes[0].shape.length, 0.08);
  EXPECT_TRUE(base.collision.shapes[0].origin.translation().isApprox(Eigen::Vector3d(0, 0, 0.04)));
  const auto& shoulder = model->link("shoulder_link").collision.shapes;
  ASSERT_EQ(shoulder.size(), 1u);
  EXPECT_EQ(shoulder[0].shape.type, Shape::Type::kSphere);
  EXPECT_DOUBLE_EQ(shoulder[0].shape.radius, 0.07);
  const auto& wrist = model->link("wrist_1_link").collision.shapes;
  ASSERT_EQ(wrist.size(), 1u);
  EXPECT_EQ(wrist[0].shape.type, Shape::Type::kBox);
  EXPECT_TRUE(wrist[0].shape.box_size.isApprox(Eigen::Vector3d(0.08, 0.08, 0.08)));
  EXPECT_TRUE(model->link("tool0").collision.shapes.empty());
  EXPECT_EQ(model->collisionGeometry().size(), 7u);
  const JointModel& lift = model->joint("shoulder_lift_joint");
  EXPECT_DOUBLE_EQ(lift.limits.velocity, 3.15);
  EXPECT_DOUBLE_EQ(lift.limits.effort, 150.0);
}

TEST(RobotModel, MeshesResolveThroughPackagePaths) {
  const auto model = RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf", testResolver());
  const auto& shapes = model->link("wrist_3_link").collision.shapes;
  ASSERT_EQ(shapes.size(), 1u);
  EXPECT_EQ(shapes[0].shape.type, Shape::Type::kMesh);
  EXPECT_TRUE(std::filesystem::path(shapes[0].shape.mesh_path).is_absolute());
  EXPECT_TRUE(std::filesystem::exists(shapes[0].shape.mesh_path));
  EXPECT_EQ(std::filesystem::path(shapes[0].shape.mesh_path).filename(), "flange.stl");
  EXPECT_TRUE(shapes[0].shape.mesh_scale.isApprox(Eigen::Vector3d::Constant(0.001)));

  const auto from_map = RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf",
                                              PackageResolver::fromMap({{"sixdof_core", kDataDir + "/../.."}}));
  EXPECT_TRUE(std::filesystem::equivalent(from_map->link("wrist_3_link").collision.shapes[0].shape.mesh_path,
                                          shapes[0].shape.mesh_path));
  auto from_path = PackageResolver::fromRosPackagePath("/nonexistent:" + kDataDir + "/../../..");
  from_path.addPackage("fixtures", kDataDir);
  EXPECT_TRUE(std::filesystem::exists(from_path.resolve("package://fixtures/meshes/flange.stl")));
  EXPECT_TRUE(std::filesystem::exists(from_path.resolve("package://sixdof_core/test/data/meshes/flange.stl")));

  try {
    RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf");
    ADD_FAILURE() << "a mesh of an unknown package must not load";
  } catch (const RobotModelError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("wrist_3_link"), std::string::npos) << message;
    EXPECT_NE(message.find("package 'sixdof_core' not found"), std::string::npos) << message;
  }
  EXPECT_THROW(testResolver().resolve("package://sixdof_core/missing.stl"), RobotModelError);
  EXPECT_THROW(testResolver().resolve("relative/file.stl"), RobotModelError);
}

TEST(RobotModel, ContinuousJointsAreUnbounded) {
  const auto model = urModel();
  const JointModel& pan = model->joint("shoulder_pan_joint");
  EXPECT_EQ(pan.type, JointType::kContinuous);
  EXPECT_FALSE(pan.limits.bounded);
  EXPECT_TRUE(pan.isMultiTurn());
  expectBoundsCheck(model, "shoulder_pan_joint", 10.0, "elbow_joint", 3.5);
}

TEST(RobotState, MimicJointsAndNamedStates) {
  const auto model = armModel();
  RobotState state(model);
  EXPECT_TRUE(state.positions().isZero());
  EXPECT_TRUE(state.setToNamedState("gripper", "open"));
  EXPECT_DOUBLE_EQ(state.jointPosition("finger1_joint"), 0.04);
  EXPECT_DOUBLE_EQ(state.jointPosition("finger2_joint"), 0.04);
  EXPECT_FALSE(state.setToNamedState("gripper", "nope"));
  state.setJointPosition("finger1_joint", 0.0);
  const Eigen::Vector3d f1_closed = state.linkTransform("finger1").translation();
  const Eigen::Vector3d f2_closed = state.linkTransform("finger2").translation();
  state.setJointPosition("finger1_joint", 0.02);
  EXPECT_DOUBLE_EQ(state.jointPosition("finger2_joint"), 0.02);
  // finger1 moves along +y of the palm, finger2 (mimicking it) along -y; at zero arm joints the
  // palm's y is the base's y.
  EXPECT_TRUE((state.linkTransform("finger1").translation() - f1_closed).isApprox(Eigen::Vector3d(0, 0.02, 0)));
  EXPECT_TRUE((state.linkTransform("finger2").translation() - f2_closed).isApprox(Eigen::Vector3d(0, -0.02, 0)));

  Eigen::VectorXd arm(6);
  arm << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
  state.setGroupPositions("arm", arm);
  EXPECT_TRUE(state.groupPositions("arm").isApprox(arm));
  EXPECT_DOUBLE_EQ(state.positions()[6], 0.02);
  EXPECT_THROW(state.setGroupPositions("arm", Eigen::VectorXd::Zero(5)), std::invalid_argument);
  EXPECT_THROW(state.setGroupPositions("nope", arm), std::invalid_argument);
  EXPECT_THROW(state.setJointPosition("finger2_joint", 0.0), std::invalid_argument);
  EXPECT_THROW(state.setJointPosition("joint1", std::nan("")), std::invalid_argument);
  EXPECT_THROW(state.setPositions(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  EXPECT_THROW(state.linkTransform("nope"), std::out_of_range);
}

TEST(RobotModelErrors, SrdfProblemsAreNamed) {
  expectSrdfError("<robot name=\"sixdof\"><group name=\"arm\">", "XML error");
  expectSrdfError("<robot name=\"other\"/>", "robot name 'other' does not match");
  expectSrdfError(srdfWith("<group name=\"arm\"><chain base_link=\"base_link\" tip_link=\"link7\"/></group>"),
                  "group 'arm' chain refers to unknown link 'link7'");
  expectSrdfError(srdfWith("<group name=\"arm\"><chain base_link=\"link6\" tip_link=\"base_link\"/></group>"),
                  "'base_link' is not a descendant of 'link6'");
  expectSrdfError(srdfWith("<group name=\"arm\"><joint name=\"joint9\"/></group>"),
                  "group 'arm' refers to unknown joint 'joint9'");
  expectSrdfError(srdfWith("<group name=\"arm\"><link name=\"nolink\"/></group>"),
                  "group 'arm' refers to unknown link 'nolink'");
  expectSrdfError(srdfWith("<group name=\"all\"><group name=\"missing\"/></group>"),
                  "group 'all' refers to unknown subgroup 'missing'");
  expectSrdfError(srdfWith("<group name=\"a\"><group name=\"b\"/></group>"
                           "<group name=\"b\"><group name=\"a\"/></group>"),
                  "contains itself");
  expectSrdfError(srdfWith("<group name=\"arm\"><joint name=\"joint1\"/></group>"
                           "<group name=\"arm\"><joint name=\"joint2\"/></group>"),
                  "group 'arm' is declared twice");
  expectSrdfError(srdfWith("<group_state name=\"home\" group=\"nogroup\"/>"),
                  "group_state 'home' refers to unknown group 'nogroup'");
  expectSrdfError(srdfWith("<group name=\"arm\"><joint name=\"joint1\"/></group>"
                           "<group_state name=\"home\" group=\"arm\">"
                           "<joint name=\"joint2\" value=\"0\"/></group_state>"),
                  "sets joint 'joint2', which is not in the group");
  expectSrdfError(srdfWith("<group name=\"arm\"><joint name=\"joint2\"/></group>"
                           "<group_state name=\"home\" group=\"arm\">"
                           "<joint name=\"joint2\" value=\"2.5\"/></group_state>"),
                  "outside its limits");
  expectSrdfError(srdfWith("<group name=\"arm\"><joint name=\"joint2\"/></group>"
                           "<group_state name=\"home\" group=\"arm\">"
                           "<joint name=\"joint2\" value=\"x\"/></group_state>"),
                  "is not a number");
  expectSrdfError(srdfWith("<end_effector name=\"hand\" parent_link=\"link6\" group=\"nogroup\"/>"),
                  "end effector 'hand' refers to unknown group 'nogroup'");
  expectSrdfError(srdfWith("<end_effector name=\"hand\" parent_link=\"link66\" group=\"g\"/>"),
                  "end effector 'hand' refers to unknown link 'link66'");
  expectSrdfError(srdfWith("<virtual_joint name=\"v\" type=\"floating\" parent_frame=\"world\" child_link=\"link1\"/>"),
                  "not the URDF root link");
  expectSrdfError(
      srdfWith("<virtual_joint name=\"v\" type=\"wobbly\" parent_frame=\"world\" child_link=\"base_link\"/>"),
                  "unknown type 'wobbly'");
  expectSrdfError(srdfWith("<disable_collisions link1=\"link1\" link2=\"linkX\" reason=\"Never\"/>"),
                  "disable_collisions refers to unknown link 'linkX'");
  expectSrdfError(srdfWith("<disable_collisions link1=\"link1\" reason=\"Never\"/>"), "has no 'link2' attribute");
  expectSrdfError(srdfWith("<passive_joint name=\"jointX\"/>"), "passive joint refers to unknown joint 'jointX'");
  expectSrdfError(srdfWith("<group name=\"arm\"><chian/></group>"), "group 'arm' has an unknown element <chian>");
  expectSrdfError(srdfWith("<grup name=\"arm\"/>"), "unknown element <grup>");
}

TEST(RobotModelErrors, UrdfProblemsAreNamed) {
  EXPECT_THROW(RobotModel("<robot name=\"x\"><link name=\"a\"/>", "<robot name=\"x\"/>"), RobotModelError);
  const std::string two_roots =
      "<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
      "<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"nolink\"/></joint></robot>";
  expectModelError(two_roots, "<robot name=\"x\"/>", "nolink");
  const std::string bad_mimic =
      "<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"j\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/><axis xyz=\"1 0 0\"/>"
      "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"ghost\"/></joint></robot>";
  expectModelError(bad_mimic, "<robot name=\"x\"/>", "mimics unknown joint 'ghost'");
  EXPECT_THROW(readTextFile("/nonexistent/file.urdf"), RobotModelError);
}

}  // namespace
}  // namespace sixdof_core
