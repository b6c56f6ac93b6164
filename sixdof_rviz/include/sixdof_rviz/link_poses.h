#pragma once

#include <map>
#include <string>

#include <Eigen/Geometry>
#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

using LinkPoseMap = std::map<std::string, Eigen::Isometry3d, std::less<std::string>,
                             Eigen::aligned_allocator<std::pair<const std::string, Eigen::Isometry3d>>>;

// Forward kinematics over the URDF tree: the pose of every link relative to the root link.
// Joints absent from the values are at 0; mimic joints follow their master (multiplier, offset).
class LinkPoses {
 public:
  explicit LinkPoses(urdf::ModelInterfaceSharedPtr model);

  LinkPoseMap compute(const JointValues& values) const;
  const std::string& rootLink() const { return root_link_; }

 private:
  void descend(const urdf::Link& link, const Eigen::Isometry3d& pose, const JointValues& values,
               LinkPoseMap* out) const;
  double jointValue(const urdf::Joint& joint, const JointValues& values) const;

  urdf::ModelInterfaceSharedPtr model_;
  std::string root_link_;
};

}  // namespace sixdof_rviz
