#pragma once
// Default inputs of the core's benchmarks: the sixdof description of the checkout they were built from, so that
// they run without a ROS package path (`make bench` runs them from the install space of this checkout).

#include <string>

namespace sixdof_core::bench {

// The repository root: this header is <root>/src/sixdof_core/bench/bench_paths.h.
inline std::string repoRoot() {
  const std::string source(__FILE__);
  return source.substr(0, source.rfind("/src/sixdof_core/"));
}

// The package folder that package://sixdof_description/ URIs resolve against.
inline std::string descriptionDir() { return repoRoot() + "/sixdof_description"; }
inline std::string defaultUrdf() { return descriptionDir() + "/urdf/sixdof.urdf"; }
inline std::string defaultSrdf() { return descriptionDir() + "/config/sixdof.srdf"; }

}  // namespace sixdof_core::bench
