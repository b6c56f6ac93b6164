#pragma once
// Private: the <gazebo> extensions of a URDF that urdfdom (and so the core model) skips, read from the URDF's
// <robot> element. describeRobot (urdf_loader.cpp) reads them all in its one tinyxml2 pass over the text.

#include <tinyxml2.h>

#include <optional>
#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Parses urdf_xml into doc and returns its <robot> element; std::invalid_argument when the text is not XML or has no
// <robot>.
const tinyxml2::XMLElement& parseUrdfRobot(tinyxml2::XMLDocument& doc, const std::string& urdf_xml);

// The <plugin name="name"> in the robot's <gazebo> blocks, nullptr without one; std::invalid_argument when there is
// more than one.
const tinyxml2::XMLElement* findGazeboPlugin(const tinyxml2::XMLElement& robot, const std::string& name);

// The gazebo_grasp_fix plugin block, nullopt without one; throws as parseGraspFixConfig (grasp_fix.cpp).
std::optional<GraspFixConfig> readGraspFixPlugin(const tinyxml2::XMLElement& robot);

}  // namespace sixdof_sim
