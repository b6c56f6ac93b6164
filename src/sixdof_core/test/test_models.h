#pragma once
// Test helper: the fixture robots of the model, kinematics and IK tests (the sixdof arm with test/data/sixdof.srdf,
// the UR-like arm of test/data), so each test file names them instead of loading them its own way.
#include <string>

#include "sixdof_core/robot_model.h"

namespace sixdof_test {

inline const std::string kDataDir = SIXDOF_TEST_DATA_DIR;
inline const std::string kArmUrdf = std::string(SIXDOF_DESCRIPTION_DIR) + "/urdf/sixdof.urdf";

// The arm's meshes (in the generated URDF) are package://sixdof_description URIs.
inline sixdof_core::PackageResolver armResolver() {
  return sixdof_core::PackageResolver::fromMap({{"sixdof_description", SIXDOF_DESCRIPTION_DIR}});
}

inline sixdof_core::RobotModelConstPtr armModel() {
  return sixdof_core::RobotModel::fromFiles(kArmUrdf, kDataDir + "/sixdof.srdf", armResolver());
}

// test/data -> sixdof_core -> src: the folder that holds the sixdof_core package (the UR-like meshes).
inline sixdof_core::PackageResolver testResolver() {
  return sixdof_core::PackageResolver::fromSearchRoots({kDataDir + "/../../.."});
}

inline sixdof_core::RobotModelConstPtr urModel() {
  return sixdof_core::RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf", testResolver());
}

}  // namespace sixdof_test
