#pragma once
// The suction cup: its configuration (a config package's grasping.yaml `suction:` mapping, or the URDF's
// <gazebo><plugin name="sixdof_suction"> block, which wins) and, in the World (World::setVacuum), its rules:
// - The cup's face is the plane through the cup link's origin; its axis, the link's +z, points out of the cup.
// - With the vacuum on and nothing held, after every physics step a ray along the axis through the face's centre,
//   from contact_distance behind the face to contact_distance in front of it, looks for a dynamic object. The cup
//   seals on the first one hit when the surface normal there is within tilt_tolerance of the reversed axis (the cup
//   is square to the face it touches, whichever way the object lies).
// - An object heavier than max_payload is refused: nothing is attached, it stays where it is, and
//   World::suctionRefused names it while the cup touches it.
// - A seal fixes the object to the cup link at its current relative pose (a fixed constraint, as the grasp fix's)
//   and queues an ATTACHED grasp event (arm_name, palm_link = gripper_links[0] = cup_link); the vacuum going off,
//   deleting or teleporting the object releases it with a DETACHED event.
// - While held, the object and the cup link's Bullet body do not collide (it touches the cup's face; their contacts
//   would fight the constraint and turn the arm's wrist); they collide again once it is released.
// - The vacuum is commanded through <controller>/gripper_cmd (control_msgs/GripperCommand) by the node:
//   command.position > 0 turns it on, <= 0 off.

#include <optional>
#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Throws std::invalid_argument naming the field: an empty cup_link or controller, max_payload <= 0,
// tilt_tolerance outside (0, pi/2], contact_distance outside (0, 0.02] m.
void validateSuctionConfig(const SuctionConfig& config);

// The `suction` mapping of a grasping.yaml (keys arm_name, cup_link, max_payload, tilt_tolerance, contact_distance,
// controller; cup_link is required, the others default as in SuctionConfig); nullopt when there is none. Throws
// std::invalid_argument naming `source` and the key on unreadable YAML, an unknown key, a value of the wrong type and
// what validateSuctionConfig refuses.
std::optional<SuctionConfig> parseSuctionYaml(const std::string& yaml_text, const std::string& source);

// The URDF's <gazebo><plugin name="sixdof_suction"> block (child elements named as the YAML keys); nullopt without
// one. Throws std::invalid_argument naming the element on a malformed block or several blocks.
std::optional<SuctionConfig> parseSuctionPlugin(const std::string& urdf_xml);

// A config package's grasping.yaml: its grasp fix (parseGraspingYaml, grasp_fix.h) and its suction cup, each when
// present. Throws std::invalid_argument naming `source` when it has neither or either is malformed.
struct GraspingConfig {
  std::optional<GraspFixConfig> grasp_fix;
  std::optional<SuctionConfig> suction;
};
GraspingConfig parseGraspingConfig(const std::string& yaml_text, const std::string& source);

}  // namespace sixdof_sim
