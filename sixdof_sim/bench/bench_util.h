#pragma once
// Helpers the simulator's benchmarks share.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sixdof_sim::bench {

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// The install space's share directory: <prefix>/lib/sixdof_sim/<benchmark> -> <prefix>/share.
inline std::filesystem::path shareDir() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().parent_path().parent_path() / "share";
}

}  // namespace sixdof_sim::bench
