#pragma once

#include <map>
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "sixdof_core/robot_model.h"
#include "sixdof_rviz/semantic_model.h"

namespace sixdof_rviz {

using LinkPoseMap = std::map<std::string, Eigen::Isometry3d, std::less<std::string>,
                             Eigen::aligned_allocator<std::pair<const std::string, Eigen::Isometry3d>>>;

// Forward kinematics of the core robot model (sixdof_core::RobotState): the pose of every link relative to the
// root link. Active joints absent from the values are at the model's default position (0 when within the
// limits); mimic joints follow their master; names of other joints are ignored.
class LinkPoses {
 public:
  explicit LinkPoses(std::shared_ptr<const sixdof_core::RobotModel> model);

  // Throws std::invalid_argument on a non-finite value.
  LinkPoseMap compute(const JointValues& values) const;
  const std::string& rootLink() const { return model_->rootLink(); }

 private:
  std::shared_ptr<const sixdof_core::RobotModel> model_;
};

}  // namespace sixdof_rviz
