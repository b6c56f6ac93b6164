#pragma once
// Test helper: the sixdof arm's package folder, sixdof_description, as the sourced workspace has it (found on
// ROS_PACKAGE_PATH when a test runs). sixdof_description depends on this package (its generator runs the core), so
// it is built after it and CMake cannot hand its folder to these tests.
#include <cstdlib>
#include <string>

#include "sixdof_core/robot_model.h"

namespace sixdof_test {

// Throws RobotModelError naming the package and the folders searched when it is not on ROS_PACKAGE_PATH.
inline std::string descriptionDir() {
  const char* path = std::getenv("ROS_PACKAGE_PATH");
  return sixdof_core::PackageResolver::fromRosPackagePath(path ? path : "").packageDirectory("sixdof_description");
}

}  // namespace sixdof_test
