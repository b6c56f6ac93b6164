#pragma once
// Grasp-fix configuration from the URDF (gazebo_grasp_fix plugin block). The grasp fix itself runs
// inside World (World::setGraspFixEnabled, World::takeGraspEvents).

#include <optional>
#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Reads <gazebo><plugin name="gazebo_grasp_fix" ...><arm>...</arm></plugin></gazebo> from URDF text.
// Returns nullopt when the URDF has no such plugin. Throws std::invalid_argument naming the problem
// on a malformed block (missing palm_link / gripper_link, unparsable numbers, angle tolerance < 90,
// update_rate <= 0, max_grip_count < grip_count_threshold, several <arm> blocks).
std::optional<GraspFixConfig> parseGraspFixConfig(const std::string& urdf_xml);

}  // namespace sixdof_sim
