#pragma once
// World files (YAML, documented in worlds/README.md) -> WorldSpec.

#include <stdexcept>
#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// A world file that cannot be used. what() names the file, the entry and the problem,
// e.g. "table_top.yaml: objects[2] (red_cube): 'mass' must be > 0 for a dynamic object".
class WorldFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses YAML text; source_name prefixes error messages.
WorldSpec parseWorldYaml(const std::string& yaml_text, const std::string& source_name = "<string>");
// Reads and parses a world file.
WorldSpec loadWorldFile(const std::string& path);

}  // namespace sixdof_sim
