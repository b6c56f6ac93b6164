#pragma once
// The grasp fix (a re-implementation of gazebo_grasp_fix's semantics): its configuration from the
// URDF, and its decision logic. World feeds it the gripper/object contacts of every physics step and
// applies its attach/detach decisions as fixed constraints (World::setGraspFixEnabled,
// World::takeGraspEvents). The logic needs no Bullet, so it is tested on its own as well.
//
// Semantics (all times are SIMULATED time):
// - Contacts between a gripper link and a dynamic object are accumulated per (object, link): the
//   mean force on the object, the mean contact point and the object origin in the link's frame.
//   A step's force is the link's total over its contact points (World), where the original averages
//   each contact's force over its points: Bullet keeps 1-4 points per pair depending on the contact's
//   shape, and per-point means of a balanced grip on a cylinder (a line contact: several points on
//   one finger, one on the other) differed up to 4x and failed the 0.3 ratio below.
// - Every 1/update_rate s: an object is gripped when two per-link mean forces (each > 1e-4 N) make
//   an angle > forces_angle_tolerance and the shorter is >= 0.3 x the longer. Gripped objects gain a
//   count (capped at max_grip_count), others lose one. An object whose count exceeds
//   grip_count_threshold while nothing is attached gets attached at its current pose relative to
//   the palm; the window's per-link contact data is kept as the attach reference.
// - Release: an attached object is released as soon as, for any reference link, the distance from
//   the reference contact point (moving with the link) to the object origin differs from its
//   attach-time value by more than release_tolerance (the fingers opened). Unlike the original this
//   is checked after every physics step and not only once the count has decayed, so the object
//   drops within a few milliseconds of the fingers opening instead of 1-2 s later.
// - No flapping: after a release the object's count restarts at zero, so it must be gripped for
//   grip_count_threshold + 1 further updates before it can be attached again.

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Reads <gazebo><plugin name="gazebo_grasp_fix" ...><arm>...</arm></plugin></gazebo> from URDF text.
// Returns nullopt when the URDF has no such plugin. Throws std::invalid_argument naming the problem
// on a malformed block (missing palm_link / gripper_link, unparsable numbers, angle tolerance < 90,
// update_rate <= 0, max_grip_count < grip_count_threshold, several <arm> blocks).
std::optional<GraspFixConfig> parseGraspFixConfig(const std::string& urdf_xml);

// The grasp fix of a config package's grasping.yaml (written by sixdof_core's setup assistant): its `grasp_fix`
// mapping with palm_link, gripper_links and optionally arm_name and gazebo_grasp_fix's parameters, each missing
// one at the plugin's own default (as for the URDF block). Throws std::invalid_argument naming `source` and the key
// on YAML that cannot be read, a missing mapping or link, an unknown key, a value of the wrong type, and what
// validateGraspFixConfig refuses.
GraspFixConfig parseGraspingYaml(const std::string& yaml_text, const std::string& source);

// Throws std::invalid_argument naming the problem when a config is unusable (same checks as above).
void validateGraspFixConfig(const GraspFixConfig& config);

// One (object, gripper link) contact pair during one physics step.
struct GraspContact {
  std::string object;
  std::string link;
  Eigen::Vector3d force_on_object = Eigen::Vector3d::Zero();  // N, world frame, the link's total (all points)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();            // world frame, mean contact point
};

struct GraspDecision {
  std::vector<std::string> attach;  // attach these to the palm now (at most one: one gripper)
  std::vector<std::string> detach;  // release these now
};

class GraspFix {
 public:
  // World pose of a link / an object by name; false if unknown.
  using PoseLookup = std::function<bool(const std::string& name, Eigen::Isometry3d* pose)>;

  GraspFix(const GraspFixConfig& config, PoseLookup link_pose, PoseLookup object_pose);

  // After every physics step: that step's contacts and the sim time at its end. Contacts of links that
  // are not gripper links are ignored.
  GraspDecision update(double sim_time, const std::vector<GraspContact>& contacts);
  // Forget an object (deleted or teleported; the caller releases it if it was attached).
  void forget(const std::string& object);
  // Initial state: nothing attached, no counts, no contacts, first update at time 0 + period.
  void reset();

  const GraspFixConfig& config() const { return config_; }
  const std::string& attached() const { return attached_; }  // empty if none
  int gripCount(const std::string& object) const;

 private:
  struct Accumulated {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d point_in_link = Eigen::Vector3d::Zero();
    Eigen::Vector3d object_in_link = Eigen::Vector3d::Zero();
    int samples = 0;
  };
  using LinkContacts = std::map<std::string, Accumulated>;  // by gripper link

  bool isGripped(const LinkContacts& links) const;
  bool shouldRelease() const;

  GraspFixConfig config_;
  PoseLookup link_pose_;
  PoseLookup object_pose_;
  double period_;
  double next_update_ = 0.0;
  std::map<std::string, LinkContacts> window_;  // contacts accumulated since the last update
  std::map<std::string, int> grip_counts_;
  std::string attached_;
  LinkContacts attach_reference_;
};

}  // namespace sixdof_sim
