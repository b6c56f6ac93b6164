#pragma once
// URDF -> a plain robot description for the Bullet world (urdfdom for the model, tinyxml2 for the
// <gazebo> extensions urdfdom skips). No Bullet types here.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

struct RobotCollision {
  Shape shape;                                               // kMesh keeps the URI unresolved
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // in the link frame
};

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
  std::vector<RobotLink> links;    // parents before children (root first)
  std::vector<RobotJoint> joints;  // joints[i] has child links[i + 1]; same order as links
  std::optional<GraspFixConfig> grasp_fix;
};

// Throws std::invalid_argument naming the problem: unparsable URDF, floating/planar/continuous-less
// unsupported joint types, a moving link without mass, non-symmetric/negative inertia, mimic of an
// unknown joint, <mu1> that is not a non-negative number, a malformed grasp-fix block.
RobotDescription parseRobotDescription(const std::string& urdf_xml);

}  // namespace sixdof_sim
