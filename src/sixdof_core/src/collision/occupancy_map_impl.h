#pragma once

// The occupancy map's private state: the OctoMap tree. The collision scene reads it through
// OccupancyMapAccess to build FCL's OcTree geometry over the same (immutable once shared) tree.

#include <memory>

#include <octomap/OcTree.h>

#include "sixdof_core/occupancy_map.h"

namespace sixdof_core {

struct OccupancyMap::Impl {
  std::shared_ptr<octomap::OcTree> tree;
};

namespace detail {

struct OccupancyMapAccess {
  static std::shared_ptr<const octomap::OcTree> tree(const OccupancyMap& map) { return map.impl_->tree; }
};

}  // namespace detail
}  // namespace sixdof_core
