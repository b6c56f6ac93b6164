#pragma once
// Private: URI resolution of world-file meshes (the meshes themselves load with sixdof_core::loadMesh).

#include <string>
#include <vector>

namespace sixdof_sim {

// Resolves package://pkg/rel (against <root>/pkg/rel, or <root>/rel when root's last component is pkg),
// file:///abs and plain paths. Returns the existing file path, or an empty string.
std::string resolveResource(const std::string& uri, const std::vector<std::string>& search_roots);

}  // namespace sixdof_sim
