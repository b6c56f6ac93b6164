#pragma once
// Test helper: the fixture robots of the model, kinematics and IK tests (the sixdof arm with test/data/sixdof.srdf,
// the UR-like arm of test/data), so each test file names them instead of loading them its own way.
#include <gtest/gtest.h>

#include <string>

#include "sixdof_core/robot_model.h"
#include "test_description.h"

// In namespace sixdof_core, where the tests are, so that they name these without a using-declaration.
namespace sixdof_core {

inline const std::string kDataDir = SIXDOF_TEST_DATA_DIR;
inline std::string armUrdf() { return sixdof_test::descriptionDir() + "/urdf/sixdof.urdf"; }

// The arm's meshes (in the generated URDF) are package://sixdof_description URIs.
inline PackageResolver armResolver() {
  return PackageResolver::fromMap({{"sixdof_description", sixdof_test::descriptionDir()}});
}

inline RobotModelConstPtr armModel() {
  return RobotModel::fromFiles(armUrdf(), kDataDir + "/sixdof.srdf", armResolver());
}

// test/data -> sixdof_core -> src: the folder that holds the sixdof_core package (the UR-like meshes).
inline PackageResolver testResolver() {
  return PackageResolver::fromSearchRoots({kDataDir + "/../../.."});
}

inline RobotModelConstPtr urModel() {
  return RobotModel::fromFiles(kDataDir + "/ur_like.urdf", kDataDir + "/ur_like.srdf", testResolver());
}

// RobotState::satisfiesBounds on a model's joint kinds: the continuous joint `multi_turn` set to `far` (past pi)
// stays within bounds, the bounded joint `bounded` set to `past` (beyond its limit) does not.
inline void expectBoundsCheck(const RobotModelConstPtr& model, const std::string& multi_turn, double far,
                              const std::string& bounded, double past) {
  RobotState state(model);
  state.setJointPosition(multi_turn, far);
  EXPECT_TRUE(state.satisfiesBounds()) << multi_turn << " = " << far;
  state.setJointPosition(bounded, past);
  EXPECT_FALSE(state.satisfiesBounds()) << bounded << " = " << past;
}

}  // namespace sixdof_core
