#pragma once
// Default inputs of the core's benchmarks: the sixdof arm of the sourced workspace (sixdof_description, found on
// ROS_PACKAGE_PATH; `make bench` runs them in this checkout's install space). sixdof_description depends on this
// package, so it is built after it and CMake cannot hand its folder to them.

#include <cstdlib>
#include <string>

#include "sixdof_core/robot_model.h"

namespace sixdof_core::bench {

// The package folder that package://sixdof_description/ URIs resolve against; throws RobotModelError naming the
// folders searched when it is not on ROS_PACKAGE_PATH.
inline std::string descriptionDir() {
  const char* path = std::getenv("ROS_PACKAGE_PATH");
  return PackageResolver::fromRosPackagePath(path ? path : "").packageDirectory("sixdof_description");
}
inline std::string defaultUrdf() { return descriptionDir() + "/urdf/sixdof.urdf"; }
inline std::string defaultSrdf() { return descriptionDir() + "/config/sixdof.srdf"; }

}  // namespace sixdof_core::bench
