#pragma once

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/geometry.h"

namespace sixdof_core {

// Thrown on a malformed URDF/SRDF or an unresolvable mesh; the message names the problem.
class RobotModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic };
// The URDF name: "fixed", "revolute", "continuous", "prismatic".
const char* toString(JointType type);

struct JointLimits {
  // The one convention of every package (docs/design.md, "Joint limits"), MoveIt's: a continuous joint is
  // unbounded (bounded = false, no position limit is enforced anywhere) and lower/upper are then -pi/pi,
  // the range random sampling uses and displays show.
  bool bounded = true;
  double lower = 0.0;
  double upper = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
};

struct MimicInfo {
  std::string joint;  // the joint this one follows: value = multiplier * joint + offset
  double multiplier = 1.0;
  double offset = 0.0;
  int joint_index = -1;  // index of `joint` in RobotModel::joints(), set by the model
};

struct JointModel {
  std::string name;
  JointType type = JointType::kFixed;
  std::string parent_link;
  std::string child_link;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame at zero, in the parent link frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           // unit, in the joint (child) frame
  JointLimits limits;
  double damping = 0.0;   // URDF <dynamics damping> (N s/m or N m s/rad); the simulator applies it
  double friction = 0.0;  // URDF <dynamics friction> (N or N m, Coulomb)
  std::optional<MimicInfo> mimic;
  int variable_index = -1;  // index in RobotState::positions(); -1 for fixed and mimic joints

  bool isActive() const { return variable_index >= 0; }
  // More than one turn of travel: IK must consider 2*pi multiples of a solution.
  bool isMultiTurn() const;
};

// A link's URDF <inertial>: mass, centre of mass and inertia about it.
struct LinkInertial {
  double mass = 0.0;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // the inertial frame in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         // about the centre of mass, inertial-frame axes
};

// A URDF <visual>: its shape in the link frame and its material colour when it has one. A visual mesh that
// cannot be resolved keeps an empty mesh_path (planning needs no visuals; a renderer reports it).
struct LinkVisual {
  PlacedShape placed;
  std::optional<Eigen::Vector4d> rgba;
};

struct LinkModel {
  std::string name;
  int parent_joint = -1;  // index into RobotModel::joints(); -1 for the root link
  int parent_link = -1;   // index into RobotModel::links(); -1 for the root link
  std::vector<int> child_joints;
  LinkGeometry collision;  // shapes in the link frame; empty for links without collision geometry
  std::optional<LinkInertial> inertial;  // absent for links without <inertial>
  std::vector<LinkVisual> visuals;       // in URDF order; empty for links without <visual>
};

// An SRDF planning group. joints/links are the fully expanded contents (chains and subgroups included),
// in model order.
struct JointGroup {
  std::string name;
  std::vector<std::string> joints;         // every joint of the group, including fixed and mimic ones
  std::vector<std::string> active_joints;  // the group's variables, in model order
  std::vector<std::string> links;
  std::vector<std::string> subgroups;
  std::string chain_base;  // set when the group is declared as a <chain>
  std::string chain_tip;

  bool isChain() const { return !chain_tip.empty(); }
};

struct GroupState {
  std::string name;
  std::string group;
  std::map<std::string, double> values;  // joint name -> position
};

struct EndEffector {
  std::string name;
  std::string parent_link;
  std::string group;
  std::string parent_group;  // may be empty
};

struct VirtualJoint {
  std::string name;
  std::string type;  // fixed | floating | planar
  std::string parent_frame;
  std::string child_link;
};

struct DisabledCollisionPair {
  std::string link1;
  std::string link2;
  std::string reason;
};

// Resolves mesh URIs (package://pkg/path, file:///path, absolute paths) to existing absolute files.
class PackageResolver {
 public:
  PackageResolver() = default;
  // Each root is either a package directory or a directory containing packages (searched a few
  // levels deep), like the entries of ROS_PACKAGE_PATH.
  static PackageResolver fromSearchRoots(const std::vector<std::string>& roots);
  // Splits a ROS_PACKAGE_PATH-style string (':'-separated) into search roots.
  static PackageResolver fromRosPackagePath(const std::string& ros_package_path);
  static PackageResolver fromMap(const std::map<std::string, std::string>& package_dirs);
  // An explicit package directory, looked up before the search roots.
  PackageResolver& addPackage(const std::string& package, const std::string& directory);

  // package://pkg/path (pkg found in the explicit folders, then below the search roots), file:///abs or an absolute
  // path, to the existing file. Throws RobotModelError naming the URI when the URI is malformed or relative, the
  // package is unknown or the file does not exist.
  std::string resolve(const std::string& uri) const;
  // Throws RobotModelError when the package cannot be found.
  std::string packageDirectory(const std::string& package) const;

 private:
  std::vector<std::string> roots_;
  std::map<std::string, std::string> package_dirs_;
};

// The immutable kinematic and semantic description of the robot (URDF + SRDF), ROS-free.
class RobotModel {
 public:
  // Throws RobotModelError on malformed input, naming the problem. An empty srdf_xml gives a model without
  // semantics (no groups, states or end effectors): what a simulator needs.
  RobotModel(const std::string& urdf_xml, const std::string& srdf_xml,
             const PackageResolver& resolver = PackageResolver());
  static std::shared_ptr<const RobotModel> fromFiles(const std::string& urdf_path, const std::string& srdf_path,
                                                     const PackageResolver& resolver = PackageResolver());

  const std::string& name() const { return name_; }
  const std::string& rootLink() const { return links_.front().name; }

  // Links in breadth-first order from the root, siblings in URDF document order (every parent before its
  // children); joints in the same order: joints()[i] is the parent joint of links()[i + 1]. Every package
  // lists links and joints in this order.
  const std::vector<LinkModel>& links() const { return links_; }
  const std::vector<JointModel>& joints() const { return joints_; }
  int linkIndex(const std::string& name) const;   // -1 if unknown
  int jointIndex(const std::string& name) const;  // -1 if unknown
  const LinkModel& link(const std::string& name) const;    // throws std::out_of_range naming the link
  const JointModel& joint(const std::string& name) const;  // throws std::out_of_range naming the joint

  // The active joints (non-fixed, non-mimic): the variables of a RobotState, in this order.
  const std::vector<std::string>& variableNames() const { return variable_names_; }
  size_t variableCount() const { return variable_names_.size(); }
  const JointModel& variableJoint(size_t variable) const { return joints_[variable_joints_[variable]]; }
  // 0 where 0 is within limits, else the middle of the range.
  Eigen::VectorXd defaultPositions() const;

  // Indices of the joints on the path from base_link down to tip_link (throws if tip is not below base).
  std::vector<int> chainJoints(const std::string& base_link, const std::string& tip_link) const;

  const std::vector<JointGroup>& groups() const { return groups_; }
  const JointGroup* findGroup(const std::string& name) const;
  const std::vector<GroupState>& groupStates() const { return group_states_; }
  const GroupState* findGroupState(const std::string& group, const std::string& name) const;
  const std::vector<EndEffector>& endEffectors() const { return end_effectors_; }
  // Recorded as declared; they add no variables (link transforms are in the root link's frame).
  const std::vector<VirtualJoint>& virtualJoints() const { return virtual_joints_; }
  const std::vector<std::string>& passiveJoints() const { return passive_joints_; }
  const std::vector<DisabledCollisionPair>& disabledCollisionPairs() const { return disabled_collisions_; }

  // Collision geometry of every link that has some, in link order.
  std::vector<LinkGeometry> collisionGeometry() const;

 private:
  void parseUrdf(const std::string& urdf_xml, const PackageResolver& resolver);
  void parseSrdf(const std::string& srdf_xml);

  std::string name_;
  std::vector<LinkModel> links_;
  std::vector<JointModel> joints_;
  std::map<std::string, int> link_index_;
  std::map<std::string, int> joint_index_;
  std::vector<std::string> variable_names_;
  std::vector<int> variable_joints_;
  std::vector<JointGroup> groups_;
  std::vector<GroupState> group_states_;
  std::vector<EndEffector> end_effectors_;
  std::vector<VirtualJoint> virtual_joints_;
  std::vector<std::string> passive_joints_;
  std::vector<DisabledCollisionPair> disabled_collisions_;
};

using RobotModelConstPtr = std::shared_ptr<const RobotModel>;

// Joint positions of every active joint plus the transforms of every link (in the root link frame),
// kept consistent: every setter applies mimic joints and recomputes forward kinematics in one pass.
class RobotState {
 public:
  explicit RobotState(RobotModelConstPtr model);  // default positions

  const RobotModel& model() const { return *model_; }
  const RobotModelConstPtr& modelPtr() const { return model_; }

  const Eigen::VectorXd& positions() const { return positions_; }
  // Throws std::invalid_argument on a size mismatch or a non-finite value.
  void setPositions(const Eigen::VectorXd& positions);
  // Any joint, including mimic joints (their value derived from the source joint).
  double jointPosition(const std::string& joint) const;
  // Throws std::invalid_argument for unknown, fixed or mimic joints.
  void setJointPosition(const std::string& joint, double value);

  // The group's active joints, in JointGroup::active_joints order. Throw std::invalid_argument on
  // an unknown group or a size mismatch.
  Eigen::VectorXd groupPositions(const std::string& group) const;
  void setGroupPositions(const std::string& group, const Eigen::VectorXd& values);
  // Sets positions()[indices[i]] = values[i] and updates the link transforms, without name lookups: the
  // fast path of a planner's validity checks. Throws std::invalid_argument on a size mismatch, an index out
  // of range or a non-finite value.
  void setVariablePositions(const std::vector<int>& indices, const Eigen::VectorXd& values);
  // Applies an SRDF group_state; false when the group has no such state.
  bool setToNamedState(const std::string& group, const std::string& state);

  // Throws std::out_of_range naming an unknown link.
  const Eigen::Isometry3d& linkTransform(const std::string& link) const;
  const Eigen::Isometry3d& linkTransform(int link_index) const { return link_transforms_[link_index]; }
  const std::vector<Eigen::Isometry3d>& linkTransforms() const { return link_transforms_; }

  // True when every bounded active joint is within its limits (+- tolerance).
  bool satisfiesBounds(double tolerance = 0.0) const;

  // Geometric Jacobian (MoveIt's RobotState::getJacobian) of the point reference_point, fixed in `link`'s frame,
  // with respect to the group's active joints (columns in JointGroup::active_joints order), in the root link
  // frame: rows 0-2 linear velocity, rows 3-5 angular velocity. A group joint that does not move the link gives
  // a zero column; a mimic joint adds its multiplier times its own column to its source joint's column.
  // Throws std::invalid_argument on an unknown group, std::out_of_range on an unknown link.
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian(
      const std::string& group, const std::string& link,
      const Eigen::Vector3d& reference_point = Eigen::Vector3d::Zero()) const;

 private:
  void update();

  RobotModelConstPtr model_;
  Eigen::VectorXd positions_;
  std::vector<double> joint_values_;  // per joint (mimic applied); 0 for fixed joints
  std::vector<Eigen::Isometry3d> link_transforms_;
};

// Reads a whole text file; throws RobotModelError naming the file if it cannot be read.
std::string readTextFile(const std::string& path);

}  // namespace sixdof_core
