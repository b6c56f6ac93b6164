// URDF edits keep every byte they do not change.
#include <gtest/gtest.h>

#include <string>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/urdf_edit.h"

namespace sixdof_core {
namespace {

const char* const kUrdf = R"(<?xml version="1.0"?>
<!-- a <link name="commented"/> in a comment -->
<robot name='r'>
  <link name="base"/>
  <link name = 'empty'/>
  <link name="heavy">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <inertial>
      <mass value="0"/>
      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>
    </inertial>
  </link>
  <link name="inline"><visual><geometry><sphere radius="1"/></geometry></visual><inertial><mass value="0"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="a" type="revolute"><parent link="base"/><child link="empty"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b" type="revolute"><parent link="empty"/><child link="heavy"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="c" type="revolute"><parent link="heavy"/><child link="inline"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";

LinkInertial inertial(double mass) {
  LinkInertial i;
  i.mass = mass;
  i.origin.translation() = Eigen::Vector3d(0.1, 0, 1e-7);
  i.inertia = Eigen::Vector3d(1e-3, 2e-3, 2.5e-3).asDiagonal();
  return i;
}

TEST(UrdfEdit, InertialsAreAddedOrReplacedAndFramesAppended) {
  UrdfEdits edits;
  edits.inertials["empty"] = {inertial(1.5), "computed -- here"};
  edits.inertials["heavy"] = {inertial(2.0), ""};
  edits.inertials["inline"] = {inertial(3.0), ""};
  edits.frames.push_back({"tcp", "tcp_joint", "inline", poseFromXyzRpy(0, 0, 0.1, 0, M_PI / 2, 0)});
  const std::string out = editUrdf(kUrdf, edits);
  const RobotModel model(out, "");
  EXPECT_EQ(model.link("empty").inertial->mass, 1.5);
  EXPECT_EQ(model.link("heavy").inertial->mass, 2.0);
  EXPECT_EQ(model.link("inline").inertial->mass, 3.0);
  EXPECT_TRUE(model.link("inline").inertial->origin.translation().isApprox(Eigen::Vector3d(0.1, 0, 1e-7)));
  EXPECT_NEAR(model.link("heavy").inertial->inertia(2, 2), 2.5e-3, 1e-15);
  EXPECT_EQ(model.joint("tcp_joint").parent_link, "inline");
  EXPECT_TRUE(model.joint("tcp_joint").origin.isApprox(poseFromXyzRpy(0, 0, 0.1, 0, M_PI / 2, 0), 1e-8));
  // The note is a comment ("--" may not appear in one); the untouched parts are byte for byte the same.
  EXPECT_NE(out.find("<!-- computed - - here -->"), std::string::npos) << out;
  EXPECT_NE(out.find("<!-- a <link name=\"commented\"/> in a comment -->\n<robot name='r'>\n  <link name=\"base\"/>"),
            std::string::npos);
  EXPECT_NE(out.find("<visual><geometry><sphere radius=\"1\"/></geometry></visual><inertial>"), std::string::npos)
      << out;
  EXPECT_EQ(out.find("<mass value=\"0\"/>"), std::string::npos);
  EXPECT_EQ(out.substr(out.size() - 20), "  </joint>\n</robot>\n");
  EXPECT_EQ(editUrdf(kUrdf, UrdfEdits()), kUrdf);
}

TEST(UrdfEdit, BadInputIsNamed) {
  UrdfEdits edits;
  edits.inertials["nope"] = {inertial(1.0), ""};
  EXPECT_THROW(editUrdf(kUrdf, edits), RobotModelError);
  EXPECT_THROW(editUrdf("<robot><link", UrdfEdits()), RobotModelError);
  EXPECT_THROW(editUrdf("<model/>", UrdfEdits()), RobotModelError);
}

TEST(UrdfEdit, NumbersAreShortAndExact) {
  EXPECT_EQ(urdfNumber(0.0), "0");
  EXPECT_EQ(urdfNumber(-0.0), "0");
  EXPECT_EQ(urdfNumber(0.1), "0.1");
  EXPECT_EQ(urdfNumber(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(urdfNumber(1.5e-7), "1.5e-07");
}

}  // namespace
}  // namespace sixdof_core
