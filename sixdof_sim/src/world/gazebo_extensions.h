#pragma once
// Private: the <gazebo> extensions of a URDF that urdfdom (and so the core model) skips, read from the URDF's
// <robot> element. describeRobot (urdf_loader.cpp) reads them all in its one tinyxml2 pass over the text.

#include <tinyxml2.h>

#include <optional>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// The gazebo_grasp_fix plugin block, nullopt without one; throws as parseGraspFixConfig (grasp_fix.cpp).
std::optional<GraspFixConfig> readGraspFixPlugin(const tinyxml2::XMLElement& robot);

}  // namespace sixdof_sim
