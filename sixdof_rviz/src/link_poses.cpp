#include "sixdof_rviz/link_poses.h"

#include <stdexcept>

namespace sixdof_rviz {

LinkPoses::LinkPoses(std::shared_ptr<const sixdof_core::RobotModel> model) : model_(std::move(model)) {
  if (!model_) throw std::invalid_argument("LinkPoses: no robot model");
}

LinkPoseMap LinkPoses::compute(const JointValues& values) const {
  Eigen::VectorXd positions = model_->defaultPositions();
  for (const auto& [name, value] : values) {
    const int index = model_->jointIndex(name);
    if (index >= 0 && model_->joints()[index].isActive()) positions[model_->joints()[index].variable_index] = value;
  }
  sixdof_core::RobotState state(model_);
  state.setPositions(positions);
  LinkPoseMap out;
  for (size_t l = 0; l < model_->links().size(); ++l) out[model_->links()[l].name] = state.linkTransform(l);
  return out;
}

}  // namespace sixdof_rviz
