#pragma once
// Test helper: the fixture robots of the model, kinematics and IK tests (the sixdof arm with test/data/sixdof.srdf,
// the UR-like arm of test/data), so each test file names them instead of loading them its own way.
#include <string>

#include "sixdof_core/robot_model.h"

// In namespace sixdof_core, where the tests are, so that they name these without a using-declaration.
namespace sixdof_core {

inline const std::string kDataDir = SIXDOF_TEST_DATA_DIR;
inline const std::string kArmUrdf = std::string(SIXDOF_DESCRIPTION_DIR) + "/urdf/sixdof.urdf";

// The arm's meshes (in the generated URDF) are package://sixdof_description URIs.
inline PackageResolver armResolver() {
  return PackageResolver::fromMap({{"sixdof_description", SIXDOF_DESCRIPTION_DIR}});
}

inline RobotModelConstPtr armModel() {
  return RobotModel::fromFiles(kArmUrdf, kDataDir + "/sixdof.srdf", armResolver());
}

// test/data -> sixdof_core -> src: the folder that holds the sixdof_core package (the UR-like meshes).
inline PackageResolver testResolver() {
  return PackageResolver::fromSearchRoots({kDataDir + "/../../.."});
}

inline RobotModelConstPtr urModel() {
  return RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf", testResolver());
}

}  // namespace sixdof_core
