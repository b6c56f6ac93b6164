#pragma once
// Default inputs of the core's benchmarks: the sixdof description of the checkout they were built from, so that
// they run without a ROS package path (`make bench` runs them from the install space of this checkout).
// SIXDOF_DESCRIPTION_DIR is set by CMakeLists.txt.

#include <string>

namespace sixdof_core::bench {

// The package folder that package://sixdof_description/ URIs resolve against.
inline std::string descriptionDir() { return SIXDOF_DESCRIPTION_DIR; }
inline std::string defaultUrdf() { return descriptionDir() + "/urdf/sixdof.urdf"; }
inline std::string defaultSrdf() { return descriptionDir() + "/config/sixdof.srdf"; }

}  // namespace sixdof_core::bench
