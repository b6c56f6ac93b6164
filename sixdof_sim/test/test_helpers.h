#pragma once
// Shared fixtures of the world tests: the real URDF and default world, grasp-fix config, a numeric IK
// on the world's own forward kinematics (so the tests follow the URDF, whatever its geometry).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include <sixdof_core/robot_model.h>

#include "sixdof_sim/grasp_fix.h"
#include "sixdof_sim/world.h"
#include "sixdof_sim/world_file.h"

namespace sixdof_sim {
namespace test {

inline std::string readFile(const std::string& path) { return sixdof_core::readTextFile(path); }

// The message of the `Error` that `call` throws, "" when it throws none (any other exception passes through).
template <class Error, class Call>
std::string errorMessage(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline std::string robotUrdf() { return readFile(std::string(SIXDOF_DESCRIPTION_DIR) + "/urdf/sixdof.urdf"); }

inline std::string defaultWorldPath() { return std::string(SIXDOF_SIM_DIR) + "/worlds/table_top.yaml"; }

// The URDF's own grasp-fix block when it has one, else the paper's block from test/data.
inline GraspFixConfig graspConfig() {
  const auto own = parseGraspFixConfig(robotUrdf());
  if (own) return *own;
  return *parseGraspFixConfig(readFile(std::string(SIXDOF_TEST_DATA_DIR) + "/grasp_fix_block.urdf"));
}

inline WorldOptions options(bool grasp_fix) {
  WorldOptions o;
  o.package_search_roots = {SIXDOF_DESCRIPTION_DIR, SIXDOF_SIM_DIR};
  o.grasp_fix_enabled = grasp_fix;
  o.grasp_fix_config = graspConfig();
  return o;
}

inline Eigen::Isometry3d linkPose(const World& world, const std::string& link) {
  Eigen::Isometry3d pose;
  const Result r = world.linkPose(link, &pose);
  if (!r.ok()) throw std::runtime_error(r.message);
  return pose;
}

inline std::vector<std::string> armJoints() {
  return {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"};
}

inline std::vector<double> armPositions(const World& world) {
  std::vector<double> q;
  const std::vector<double> all = world.jointPositions();
  for (const std::string& name : armJoints()) q.push_back(all[world.jointIndex(name)]);
  return q;
}

// Damped least-squares IK of `link` to `target` using the world's FK (teleports the arm while
// solving). Returns true when position error < 1e-5 m and orientation error < 1e-4 rad; the arm is
// left at the solution.
inline bool solveIk(World& world, const std::string& link, const Eigen::Isometry3d& target, std::vector<double> q) {
  const std::vector<std::string> names = armJoints();
  auto error = [&](const std::vector<double>& qq) {
    EXPECT_TRUE(world.setJointPositions(names, qq).ok());
    const Eigen::Isometry3d pose = linkPose(world, link);
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = target.translation() - pose.translation();
    const Eigen::AngleAxisd aa(target.linear() * pose.linear().transpose());
    e.tail<3>() = aa.axis() * aa.angle();
    return e;
  };
  for (int iteration = 0; iteration < 200; ++iteration) {
    const Eigen::Matrix<double, 6, 1> e = error(q);
    if (e.head<3>().norm() < 1e-5 && e.tail<3>().norm() < 1e-4) return true;
    Eigen::Matrix<double, 6, 6> jacobian;
    for (int j = 0; j < 6; ++j) {
      std::vector<double> qj = q;
      qj[j] += 1e-6;
      jacobian.col(j) = -(error(qj) - e) / 1e-6;
    }
    const Eigen::Matrix<double, 6, 6> jjt =
        jacobian * jacobian.transpose() + 1e-6 * Eigen::Matrix<double, 6, 6>::Identity();
    const Eigen::Matrix<double, 6, 1> dq = jacobian.transpose() * jjt.ldlt().solve(e);
    for (int j = 0; j < 6; ++j) {
      const JointInfo& info = world.joints()[world.jointIndex(names[j])];
      q[j] = std::min(std::max(q[j] + dq[j], info.lower), info.upper);
    }
  }
  error(q);
  return false;
}

// Top-down grasp frame at `position`: tool z down, fingers closing along world y.
inline Eigen::Isometry3d topDown(const Eigen::Vector3d& position) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = Eigen::Vector3d(-1, 0, 0);
  t.linear().col(1) = Eigen::Vector3d(0, 1, 0);
  t.linear().col(2) = Eigen::Vector3d(0, 0, -1);
  t.translation() = position;
  return t;
}

}  // namespace test
}  // namespace sixdof_sim
