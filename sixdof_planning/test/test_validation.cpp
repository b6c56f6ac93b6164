// Request validation and the scene store against the real robot description (no ROS master needed).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <shape_msgs/SolidPrimitive.h>

#include "sixdof_planning/scene_store.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {
namespace {

const char* const kSource = "test";

sixdof_core::RobotModelConstPtr loadModel() {
  const std::string dir = SIXDOF_DESCRIPTION_DIR;
  return sixdof_core::RobotModel::fromFiles(dir + "/urdf/sixdof.urdf", dir + "/config/sixdof.srdf",
                                           sixdof_core::PackageResolver::fromMap({{"sixdof_description", dir}}));
}

geometry_msgs::Pose identity() {
  geometry_msgs::Pose pose;
  pose.orientation.w = 1.0;
  return pose;
}

moveit_msgs::CollisionObject box(const std::string& id, double x, double y, double z) {
  moveit_msgs::CollisionObject object;
  object.id = id;
  object.header.frame_id = "base_link";
  object.pose = identity();
  object.pose.position.x = x;
  object.pose.position.y = y;
  object.pose.position.z = z;
  shape_msgs::SolidPrimitive primitive;
  primitive.type = shape_msgs::SolidPrimitive::BOX;
  primitive.dimensions = {0.1, 0.1, 0.1};
  object.primitives.push_back(primitive);
  object.primitive_poses.push_back(identity());
  object.operation = moveit_msgs::CollisionObject::ADD;
  return object;
}

class ValidationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = loadModel(); }
  static sixdof_core::RobotModelConstPtr model_;
};
sixdof_core::RobotModelConstPtr ValidationTest::model_;

TEST_F(ValidationTest, PoseNeedsFiniteValuesAndAUnitQuaternion) {
  EXPECT_TRUE(isSuccess(validatePose(identity(), "pose", kSource)));
  auto pose = identity();
  pose.position.x = std::numeric_limits<double>::quiet_NaN();
  auto code = validatePose(pose, "target", kSource);
  EXPECT_EQ(code.val, ErrorCode::FAILURE);
  EXPECT_NE(code.message.find("target.position.x"), std::string::npos) << code.message;
  EXPECT_EQ(code.source, kSource);
  pose = identity();
  pose.orientation.w = 1.1;
  code = validatePose(pose, "target", kSource);
  EXPECT_EQ(code.val, ErrorCode::FAILURE);
  EXPECT_NE(code.message.find("unit quaternion"), std::string::npos) << code.message;
  pose.orientation.w = 1.0 + 0.9 * kQuaternionNormTolerance;
  EXPECT_TRUE(isSuccess(validatePose(pose, "target", kSource)));
  pose.orientation.w = 0.0;
  EXPECT_EQ(validatePose(pose, "target", kSource).val, ErrorCode::FAILURE);
}

TEST_F(ValidationTest, ScalingFactorsAreInZeroOneWithZeroMeaningOne) {
  double effective = -1.0;
  EXPECT_TRUE(isSuccess(validateScalingFactor(0.0, "f", kSource, &effective)));
  EXPECT_EQ(effective, 1.0);
  EXPECT_TRUE(isSuccess(validateScalingFactor(0.25, "f", kSource, &effective)));
  EXPECT_EQ(effective, 0.25);
  EXPECT_TRUE(isSuccess(validateScalingFactor(1.0, "f", kSource, &effective)));
  for (double bad : {1.0001, -0.1, 1e-308, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    const auto code = validateScalingFactor(bad, "max_velocity_scaling_factor", kSource, &effective);
    EXPECT_EQ(code.val, ErrorCode::FAILURE) << bad;
    EXPECT_NE(code.message.find("max_velocity_scaling_factor"), std::string::npos);
  }
}

TEST_F(ValidationTest, NamesAreCheckedAgainstTheModel) {
  EXPECT_TRUE(isSuccess(validateGroup(*model_, "arm", kSource)));
  auto code = validateGroup(*model_, "leg", kSource);
  EXPECT_EQ(code.val, ErrorCode::INVALID_GROUP_NAME);
  EXPECT_NE(code.message.find("'gripper'"), std::string::npos) << code.message;
  EXPECT_TRUE(isSuccess(validateLink(*model_, "tcp", kSource)));
  EXPECT_EQ(validateLink(*model_, "link7", kSource).val, ErrorCode::INVALID_LINK_NAME);
}

TEST_F(ValidationTest, JointStatesNeedKnownMovableJointsOnce) {
  sensor_msgs::JointState state;
  state.name = {"joint1", "finger2_joint"};
  state.position = {0.1, 0.0};
  EXPECT_TRUE(isSuccess(validateJointState(*model_, state, kSource)));
  state.position = {0.1};
  EXPECT_EQ(validateJointState(*model_, state, kSource).val, ErrorCode::INVALID_ROBOT_STATE);
  state.name = {"joint1", "joint1"};
  state.position = {0.1, 0.2};
  EXPECT_NE(validateJointState(*model_, state, kSource).message.find("twice"), std::string::npos);
  state.name = {"palm_joint"};
  state.position = {0.0};
  EXPECT_NE(validateJointState(*model_, state, kSource).message.find("fixed"), std::string::npos);
  state.name = {"joint3"};
  state.position = {std::numeric_limits<double>::infinity()};
  EXPECT_EQ(validateJointState(*model_, state, kSource).val, ErrorCode::INVALID_ROBOT_STATE);
}

TEST_F(ValidationTest, MalformedCollisionObjectsAreNamed) {
  EXPECT_TRUE(isSuccess(validateCollisionObject(box("b", 1, 0, 0), "object", kSource)));
  auto object = box("b", 1, 0, 0);
  object.primitives[0].type = shape_msgs::SolidPrimitive::CONE;
  EXPECT_NE(validateCollisionObject(object, "object", kSource).message.find("unsupported type"), std::string::npos);
  object = box("b", 1, 0, 0);
  object.primitives[0].dimensions = {0.1, 0.0, 0.1};
  EXPECT_NE(validateCollisionObject(object, "object", kSource).message.find("non-positive"), std::string::npos);
  object = box("b", 1, 0, 0);
  object.operation = 9;
  EXPECT_NE(validateCollisionObject(object, "object", kSource).message.find("unknown operation"), std::string::npos);
  object = box("m", 1, 0, 0);
  object.primitives.clear();
  object.primitive_poses.clear();
  shape_msgs::Mesh mesh;
  mesh.vertices.resize(3);
  shape_msgs::MeshTriangle triangle;
  triangle.vertex_indices = {0, 1, 3};
  mesh.triangles.push_back(triangle);
  object.meshes.push_back(mesh);
  object.mesh_poses.push_back(identity());
  const auto code = validateCollisionObject(object, "object", kSource);
  EXPECT_EQ(code.val, ErrorCode::FAILURE);
  EXPECT_NE(code.message.find("out of range"), std::string::npos) << code.message;
  moveit_msgs::CollisionObject remove_all;
  remove_all.operation = moveit_msgs::CollisionObject::REMOVE;
  EXPECT_TRUE(isSuccess(validateCollisionObject(remove_all, "object", kSource)));
}

TEST_F(ValidationTest, SceneStoreAttachesAndDetachesInPlace) {
  SceneStore store(model_);
  sixdof_core::RobotState state(model_);
  ASSERT_TRUE(isSuccess(store.applyCollisionObject(box("cube", 0.5, 0.1, 0.2), state, kSource)));
  ASSERT_EQ(store.worldObjects().size(), 1u);
  // A copy is independent of the original.
  SceneStore copy(store);
  moveit_msgs::AttachedCollisionObject attach;
  attach.link_name = "link6";
  attach.object.id = "cube";
  attach.object.operation = moveit_msgs::CollisionObject::ADD;
  attach.touch_links = {"palm", "finger1", "finger2"};
  const auto attached = copy.applyAttachedObject(attach, state, kSource);
  ASSERT_TRUE(isSuccess(attached)) << attached.message;
  EXPECT_TRUE(copy.worldObjects().empty());
  ASSERT_EQ(copy.attachedObjects().size(), 1u);
  EXPECT_EQ(copy.attachedObjects()[0].object.header.frame_id, "link6");
  EXPECT_EQ(store.worldObjects().size(), 1u);
  EXPECT_TRUE(store.attachedObjects().empty());
  // Detached at the same state, it is back where it was.
  attach.object.operation = moveit_msgs::CollisionObject::REMOVE;
  const auto detached = copy.applyAttachedObject(attach, state, kSource);
  ASSERT_TRUE(isSuccess(detached)) << detached.message;
  ASSERT_EQ(copy.worldObjects().size(), 1u);
  EXPECT_NEAR(copy.worldObjects()[0].pose.position.x, 0.5, 1e-12);
  EXPECT_NEAR(copy.worldObjects()[0].pose.position.z, 0.2, 1e-12);
  // Attaching an unknown object or to an unknown link is named.
  attach.object.operation = moveit_msgs::CollisionObject::ADD;
  attach.object.id = "sphere";
  EXPECT_EQ(copy.applyAttachedObject(attach, state, kSource).val, ErrorCode::INVALID_OBJECT_NAME);
  attach.object.id = "cube";
  attach.link_name = "hand9";
  EXPECT_EQ(copy.applyAttachedObject(attach, state, kSource).val, ErrorCode::INVALID_LINK_NAME);
}

TEST_F(ValidationTest, ObjectsAttachToLinksWithoutGeometryThroughTheirCarrier) {
  SceneStore store(model_);
  sixdof_core::RobotState state(model_);
  moveit_msgs::AttachedCollisionObject attach;
  attach.link_name = "tcp";
  attach.object = box("tool", 0.0, 0.0, 0.0);
  attach.object.header.frame_id = "tcp";
  attach.touch_links = {"tcp", "finger1", "finger2"};
  const auto attached = store.applyAttachedObject(attach, state, kSource);
  ASSERT_TRUE(isSuccess(attached)) << attached.message;
  EXPECT_EQ(store.attachedObjects()[0].link_name, "tcp");
  attach.object.operation = moveit_msgs::CollisionObject::REMOVE;
  ASSERT_TRUE(isSuccess(store.applyAttachedObject(attach, state, kSource)));
  ASSERT_EQ(store.worldObjects().size(), 1u);
  const auto& pose = store.worldObjects()[0].pose.position;
  const Eigen::Vector3d tcp = state.linkTransform("tcp").translation();
  EXPECT_NEAR(pose.x, tcp.x(), 1e-12);
  EXPECT_NEAR(pose.y, tcp.y(), 1e-12);
  EXPECT_NEAR(pose.z, tcp.z(), 1e-12);
}

TEST_F(ValidationTest, SceneStoreMovesAppendsAndReplaces) {
  SceneStore store(model_);
  sixdof_core::RobotState state(model_);
  ASSERT_TRUE(isSuccess(store.applyCollisionObject(box("cube", 0.5, 0.0, 0.2), state, kSource)));
  auto more = box("cube", 0.5, 0.0, 0.4);
  more.operation = moveit_msgs::CollisionObject::APPEND;
  ASSERT_TRUE(isSuccess(store.applyCollisionObject(more, state, kSource)));
  ASSERT_EQ(store.worldObjects()[0].primitives.size(), 2u);
  EXPECT_NEAR(store.worldObjects()[0].primitive_poses[1].position.z, 0.2, 1e-12);
  auto move = box("cube", 0.6, 0.0, 0.2);
  move.operation = moveit_msgs::CollisionObject::MOVE;
  ASSERT_TRUE(isSuccess(store.applyCollisionObject(move, state, kSource)));
  EXPECT_NEAR(store.worldObjects()[0].pose.position.x, 0.6, 1e-12);
  // 1 DELETEALL + 2 shapes.
  EXPECT_EQ(store.markers().markers.size(), 3u);
  moveit_msgs::PlanningScene replacement;
  replacement.is_diff = false;
  replacement.world.collision_objects.push_back(box("other", 0.0, 0.5, 0.1));
  ASSERT_TRUE(isSuccess(store.apply(replacement, state, kSource)));
  ASSERT_EQ(store.worldObjects().size(), 1u);
  EXPECT_EQ(store.worldObjects()[0].id, "other");
  moveit_msgs::PlanningScene with_joints;
  with_joints.is_diff = true;
  with_joints.robot_state.joint_state.name = {"joint1"};
  with_joints.robot_state.joint_state.position = {0.0};
  EXPECT_EQ(store.apply(with_joints, state, kSource).val, ErrorCode::FAILURE);
}

TEST_F(ValidationTest, FramesAreThePlanningFrameItsParentOrALink) {
  sixdof_core::RobotState state(model_);
  Eigen::Isometry3d pose;
  EXPECT_TRUE(isSuccess(SceneStore::frameTransform(state, "", kSource, &pose)));
  EXPECT_TRUE(pose.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(isSuccess(SceneStore::frameTransform(state, "world", kSource, &pose)));
  EXPECT_TRUE(isSuccess(SceneStore::frameTransform(state, "link6", kSource, &pose)));
  EXPECT_TRUE(pose.isApprox(state.linkTransform("link6")));
  const auto code = SceneStore::frameTransform(state, "moon", kSource, &pose);
  EXPECT_EQ(code.val, ErrorCode::FRAME_TRANSFORM_FAILURE);
  EXPECT_NE(code.message.find("'moon'"), std::string::npos);
}

}  // namespace
}  // namespace sixdof_planning
