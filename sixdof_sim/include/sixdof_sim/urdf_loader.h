#pragma once
// The core robot model (sixdof_core_model, the project's only URDF reader) mapped to a plain robot
// description for the Bullet world: masses, inertias and collision shapes per link, the moving joints with
// the core's limit convention. Only the <gazebo> extensions urdfdom skips (link friction, the grasp-fix block)
// are read here. No Bullet types.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "sixdof_core/geometry.h"
#include "sixdof_core/robot_model.h"
#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

using RobotCollision = sixdof_core::PlacedShape;  // in the link frame; meshes resolved to files

struct RobotLink {
  std::string name;
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();          // in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();      // about the COM, link-frame axes
  std::vector<RobotCollision> collisions;
  std::optional<double> friction;  // <gazebo reference="link"><mu1>
};

struct RobotJoint {
  JointInfo info;        // for fixed joints only name/parent_link/child_link are meaningful
  bool fixed = false;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame in the parent frame at q = 0
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();          // unit, in the child frame
};

struct RobotDescription {
  std::string name;
  std::string root_link;
  std::vector<RobotLink> links;    // the core model's link order (breadth-first, root first)
  std::vector<RobotJoint> joints;  // joints[i] has child links[i + 1]; same order as links
  std::optional<GraspFixConfig> grasp_fix;
};

// What the simulator needs beyond the model, checked here. Throws std::invalid_argument with one line naming
// the link or joint: a link moved by a joint without an <inertial> of mass > 0 ("cannot be simulated", as
// Gazebo refuses it; fixed links may go without), a negative mass or a non-positive-semi-definite inertia,
// a moving joint without an effort limit > 0 (the servo bound), negative damping or friction, <mu1> that is
// not a non-negative number or names no link, a malformed grasp-fix block.
RobotDescription describeRobot(const sixdof_core::RobotModel& model, const std::string& urdf_xml);

// The core model of urdf_xml (no SRDF: the simulator needs no semantics) through describeRobot. Mesh URIs
// resolve with `resolver`. Throws std::invalid_argument naming the problem, the model's errors included.
RobotDescription parseRobotDescription(const std::string& urdf_xml,
                                       const sixdof_core::PackageResolver& resolver = sixdof_core::PackageResolver());

}  // namespace sixdof_sim
