// get_robot_model's collision geometry (describeCollisionGeometry) against sixdof_core's RobotModel: every primitive
// kind with its pose in the link frame, a scaled mesh as the core's loader reads it, links without geometry left out.
#include <cmath>

#include <gtest/gtest.h>
#include <shape_msgs/SolidPrimitive.h>
#include <sixdof_core/mesh_loader.h>
#include <sixdof_core/robot_model.h>
#include <sixdof_msgs/GetRobotModel.h>

#include "sixdof_planning/conversions.h"
#include "sixdof_planning/query_robot_model_service_capability.h"

namespace sixdof_planning {
namespace {

using Primitive = shape_msgs::SolidPrimitive;

// One link per shape kind, each off its link origin, a link without geometry and a mesh link two collisions long.
const char* const kUrdf = R"(<robot name="shapes">
  <link name="base"><collision><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.3 0.1"/></geometry></collision></link>
  <link name="bare"/>
  <link name="column">
    <collision><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.04" length="0.5"/></geometry></collision>
  </link>
  <link name="hand">
    <collision><origin xyz="0 0.02 0.03"/>
      <geometry><mesh filename="package://sixdof_description/meshes/collision/link6.stl" scale="2 1 0.5"/></geometry>
    </collision>
    <collision><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <joint name="to_bare" type="fixed"><parent link="base"/><child link="bare"/></joint>
  <joint name="to_column" type="revolute"><parent link="base"/><child link="column"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="to_hand" type="fixed"><parent link="column"/><child link="hand"/><origin xyz="0 0 0.5"/></joint>
</robot>)";

sixdof_core::RobotModel loadModel() {
  const std::string dir = SIXDOF_DESCRIPTION_DIR;
  return sixdof_core::RobotModel(kUrdf, "<robot name=\"shapes\"/>",
                                 sixdof_core::PackageResolver::fromMap({{"sixdof_description", dir}}));
}

void expectPose(const geometry_msgs::Pose& pose, const Eigen::Isometry3d& expected) {
  EXPECT_TRUE(poseToEigen(pose).isApprox(expected, 1e-9)) << "pose " << pose;
}

TEST(QueryRobotModel, CollisionGeometryOfEveryShapeKindInTheLinkFrame) {
  const auto model = loadModel();
  std::vector<sixdof_msgs::RobotModelLinkGeometry> links;
  ASSERT_EQ(describeCollisionGeometry(model, &links), "");
  // Model order, links without <collision> left out.
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(links[0].link_name, "base");
  EXPECT_EQ(links[1].link_name, "column");
  EXPECT_EQ(links[2].link_name, "hand");

  ASSERT_EQ(links[0].primitives.size(), 1u);
  EXPECT_TRUE(links[0].meshes.empty());
  EXPECT_EQ(links[0].primitives[0].type, Primitive::BOX);
  EXPECT_EQ(links[0].primitives[0].dimensions, (std::vector<double>{0.2, 0.3, 0.1}));
  expectPose(links[0].primitive_poses[0], Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.05)));

  ASSERT_EQ(links[1].primitives.size(), 1u);
  EXPECT_EQ(links[1].primitives[0].type, Primitive::CYLINDER);
  EXPECT_EQ(links[1].primitives[0].dimensions, (std::vector<double>{0.5, 0.04}));  // height, radius
  expectPose(links[1].primitive_poses[0], Eigen::Translation3d(0.1, 0.0, 0.0) *
                                              Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitY()));

  ASSERT_EQ(links[2].primitives.size(), 1u);
  EXPECT_EQ(links[2].primitives[0].type, Primitive::SPHERE);
  EXPECT_EQ(links[2].primitives[0].dimensions, (std::vector<double>{0.03}));
  expectPose(links[2].primitive_poses[0], Eigen::Isometry3d::Identity());
  ASSERT_EQ(links[2].meshes.size(), 1u);
  ASSERT_EQ(links[2].mesh_poses.size(), 1u);
  expectPose(links[2].mesh_poses[0], Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.02, 0.03)));
  // The vertices and triangles of the core's loader, the URDF scale applied.
  const auto loaded = sixdof_core::loadMesh(std::string(SIXDOF_DESCRIPTION_DIR) + "/meshes/collision/link6.stl",
                                            Eigen::Vector3d(2.0, 1.0, 0.5));
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  const auto& mesh = links[2].meshes[0];
  ASSERT_EQ(mesh.vertices.size(), loaded.mesh->vertices.size());
  ASSERT_EQ(mesh.triangles.size(), loaded.mesh->triangles.size());
  ASSERT_FALSE(mesh.vertices.empty());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_EQ(Eigen::Vector3d(mesh.vertices[i].x, mesh.vertices[i].y, mesh.vertices[i].z), loaded.mesh->vertices[i]);
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(mesh.triangles[i].vertex_indices[k], loaded.mesh->triangles[i][k]);
  }
}

TEST(QueryRobotModel, TheModelDescriptionCarriesNoGeometry) {
  // describeRobotModel alone (a request without include_collision_geometry) leaves link_geometries empty.
  sixdof_msgs::GetRobotModelResponse response;
  describeRobotModel(loadModel(), &response);
  EXPECT_EQ(response.link_names, (std::vector<std::string>{"base", "bare", "column", "hand"}));
  EXPECT_TRUE(response.link_geometries.empty());
}

}  // namespace
}  // namespace sixdof_planning
