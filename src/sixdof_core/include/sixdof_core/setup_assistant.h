#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sixdof_core/grasp_geometry.h"
#include "sixdof_core/inertia.h"
#include "sixdof_core/robot_model.h"
#include "sixdof_core/srdf_writer.h"

namespace sixdof_core {

// Why the setup assistant disables a link pair (MoveIt Setup Assistant's reasons, and Gripper).
enum class DisableReason {
  kAdjacent,  // joined by a joint, possibly across links without collision geometry
  kDefault,   // colliding at the default state
  kAlways,    // colliding in more than always_fraction of the random samples
  kNever,     // colliding in none of the random samples
  // Two links of a gripper (an SRDF end effector's parent link and the links below it) that collide in some of
  // the samples: only the gripper's joints move them relative to each other, which no arm motion changes, so a
  // state where they touch (fingers closed on each other, a closing linkage modelled as a tree whose links meet)
  // would leave every plan from it in collision.
  kGripper,
};

// "Adjacent", "Default", "Always", "Never", "Gripper".
std::string reasonName(DisableReason reason);

struct CollisionMatrixOptions {
  // Random samples for Always/Never (MoveIt's sampling density: 1,000 low .. 100,000 high).
  std::size_t density = 10000;
  std::uint64_t seed = 0;
  double always_fraction = 0.95;
  // Called while sampling (about every 5% of the samples, and once at the end) with the samples drawn so far
  // and the density: a long run at a high density shows that it is alive.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct ComputedPair {
  std::string link1;  // the link that comes first in the model's (topological) link order
  std::string link2;
  DisableReason reason = DisableReason::kNever;
  // For Always/Never: in how many samples the pair collided; for Gripper: in how many until it could no longer be
  // Always (a pair is not checked any more from then on).
  std::size_t colliding_samples = 0;
};

struct DisabledCollisions {
  // Sorted by reason (Adjacent, Default, Always, Never, Gripper), then by the links' model order.
  std::vector<ComputedPair> disabled;
  std::size_t link_pairs = 0;    // pairs of links that both have collision geometry
  std::size_t samples = 0;       // random states drawn
  std::size_t pair_checks = 0;   // pairwise collision checks done while sampling
};

// Pairs of links with geometry that are joined by a joint once links without geometry are collapsed
// into their neighbours (parent before child in each pair, in model order).
std::vector<std::pair<std::string, std::string>> adjacentLinkPairs(const RobotModel& model);

// Every link of the model, in model order, with its collision shapes (none for links without geometry),
// so that RobotState::linkTransforms() are exactly the poses a CollisionScene built from it expects.
std::vector<LinkGeometry> allLinkGeometry(const RobotModel& model);

// Joint positions drawn uniformly within the limits of each active joint (continuous joints in [-pi, pi]);
// mimic joints follow through RobotState. The same generator state gives the same sequence on every platform.
class StateSampler {
 public:
  StateSampler(const RobotModel& model, std::uint64_t seed);
  Eigen::VectorXd sample();

 private:
  std::vector<std::pair<double, double>> bounds_;
  std::uint64_t state_;
};

// Classifies every pair of links with geometry. Throws std::invalid_argument on density 0 or
// always_fraction outside (0, 1).
DisabledCollisions computeDisabledCollisions(const RobotModelConstPtr& model, const CollisionMatrixOptions& options);

// Groups of a model without an SRDF: `arm` = chain from the root to the child of the last revolute
// (or continuous) joint; `gripper` = every other non-fixed joint; end effector `hand` (parent link = the
// arm's tip, group gripper) when there is a gripper. Throws std::invalid_argument when the model has no
// revolute joint.
void addGroupsSkeleton(const RobotModel& model, SrdfDocument& document);

struct SetupAssistantOptions {
  CollisionMatrixOptions collision;
  bool groups_skeleton = false;  // only applied when the input SRDF has no groups
};

struct SetupAssistantOutput {
  std::string srdf;
  DisabledCollisions collisions;
  bool skeleton_written = false;
  std::size_t manual_pairs_kept = 0;
};

// Computes the disabled collision pairs of the URDF's robot and merges them into srdf_in_xml (empty: no
// input SRDF). Hand-written parts of the input are kept; its disable_collisions entries with reason
// Adjacent, Default, Always, Never or Gripper are replaced by the computed set, entries with any other reason
// (e.g. User) are kept and win over a computed entry for the same pair. Throws RobotModelError or
// SrdfError on bad input, std::invalid_argument on bad options.
SetupAssistantOutput runSetupAssistant(const std::string& urdf_xml, const std::string& srdf_in_xml,
                                       const SetupAssistantOptions& options,
                                       const PackageResolver& resolver = PackageResolver());

// A mimic joint whose own limits do not hold the range its master gives it (multiplier x the master's range +
// offset). Mimic joints follow their master and are never checked against their own limits (as in MoveIt), so
// this is only worth a warning.
struct MimicLimitConflict {
  std::string joint;
  std::string master;
  double from = 0.0;  // the range the master gives it
  double to = 0.0;
  double lower = 0.0;  // its own limits
  double upper = 0.0;
};
std::vector<MimicLimitConflict> mimicLimitConflicts(const RobotModel& model);

// What the setup assistant repairs in a URDF before it writes it into a package.
struct RepairOptions {
  double density = kDefaultInertiaDensity;  // kg/m^3 of computed inertias
  std::optional<GripperQuery> gripper;       // analyse this gripper (and add its TCP frame)
  std::string tcp_joint = "tcp_joint";       // name of the fixed joint of an added TCP frame (made unique)
};

struct RepairResult {
  std::string urdf;                     // the repaired URDF (the input text where nothing was repaired)
  std::vector<InertiaRepair> inertias;  // computed inertias, written into `urdf`
  std::optional<GraspGeometry> grasp;
  // The TCP frame added to `urdf` (a link named query.tcp_link on a fixed joint below the parent link) when the
  // robot has no link of that name; empty otherwise.
  std::string tcp_frame_added;
};

// Computes the missing or unusable inertias of the moving links (inertiaRepairs) and, with a gripper, its grasp
// geometry (analyzeGripper), and writes both into the URDF text (editUrdf: computed <inertial>s with a comment
// saying where they come from; the TCP as a frame). Throws RobotModelError on a bad URDF and std::invalid_argument
// on a bad gripper query or density, naming the problem.
RepairResult repairModel(const std::string& urdf_xml, const RepairOptions& options,
                         const PackageResolver& resolver = PackageResolver());

// The repairs as YAML for the front end: `inertias` (link, problem, source, density, mass, com, inertia as ixx ixy
// ixz iyy iyz izz), `tcp_frame_added` and, with a gripper, `grasp` (every field of GraspGeometry; the TCP as xyz
// and rpy).
std::string describeRepairs(const RepairResult& result);

// What the setup assistant's front end (and a user) needs to know of a model, as YAML, read by the core so
// that no other code parses URDF/SRDF: the robot name and root link; links in model order (whether they
// have collision geometry, and their collision shapes, else their visual ones: type, sizes, origin xyz/rpy);
// joints in model order (type, links, origin xyz and rpy, axis, limits, mimic); the SRDF's groups (expanded
// joints, active joints, chain ends, and the IK solver that fits a chain: `analytic` when the closed form
// of AnalyticIkSolver applies, else `numeric`, with the reason); group states, end effectors and virtual
// joints; the mimic joints whose own limits conflict with their master's range; and, when given, the
// collision-matrix counts.
std::string describeModel(const RobotModel& model, const DisabledCollisions* collisions = nullptr);

// The command line of `rosrun sixdof_core setup_assistant_core` (the C++ half of `setup_assistant`).
struct SetupAssistantCommand {
  std::string urdf_path;
  std::string srdf_in_path;  // empty: no input SRDF
  std::string srdf_out_path;  // empty (only with describe_path): describe the model without sampling
  std::string describe_path;  // empty: no description
  SetupAssistantOptions options;
  // Repair mode (instead of srdf_out_path / describe_path): the repaired URDF and the YAML of the repairs.
  std::string urdf_out_path;
  std::string repairs_path;
  RepairOptions repair;
  bool help = false;
};

extern const char* const kSetupAssistantUsage;

// Throws std::invalid_argument naming the problem (unknown argument, missing value or required option,
// density not a whole number > 0, seed not a whole number >= 0, a malformed number of the repair options).
SetupAssistantCommand parseSetupAssistantArguments(const std::vector<std::string>& args);

// Reads the files, runs the setup assistant and writes the SRDF (and, with describe_path, the description of
// the model with the written SRDF). Without srdf_out_path: only describes the URDF (+ input SRDF) model. In repair
// mode: writes the repaired URDF and the repairs' YAML (repairModel, describeRepairs).
// package:// mesh URIs are resolved in the three folders above the URDF first, then in ROS_PACKAGE_PATH.
// Throws RobotModelError naming a file that cannot be read or written, and whatever runSetupAssistant throws.
SetupAssistantOutput runSetupAssistantOnFiles(const SetupAssistantCommand& command);

}  // namespace sixdof_core
