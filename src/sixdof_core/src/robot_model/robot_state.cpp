// RobotState: joint positions (mimic joints follow) and the link transforms of forward kinematics.
#include <cmath>
#include <stdexcept>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {
namespace {

bool isIdentityRotation(const Eigen::Matrix3d& m) {
  return m(0, 0) == 1.0 && m(1, 1) == 1.0 && m(2, 2) == 1.0 && m(0, 1) == 0.0 && m(0, 2) == 0.0 && m(1, 0) == 0.0 &&
         m(1, 2) == 0.0 && m(2, 0) == 0.0 && m(2, 1) == 0.0;
}

// t's rotation followed by `angle` about `axis` (unit, in t's frame). A coordinate axis (most joints) turns two of
// the columns in place.
void rotate(Eigen::Isometry3d* t, const Eigen::Vector3d& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (std::abs(axis[i]) != 1.0 || axis[j] != 0.0 || axis[k] != 0.0) continue;
    const double sign_s = axis[i] * s;
    const Eigen::Vector3d col_j = t->linear().col(j);
    t->linear().col(j) = c * col_j + sign_s * t->linear().col(k);
    t->linear().col(k) = c * t->linear().col(k) - sign_s * col_j;
    return;
  }
  t->linear() = t->linear() * Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

}  // namespace

RobotState::RobotState(RobotModelConstPtr model) : model_(std::move(model)) {
  if (!model_) throw std::invalid_argument("RobotState needs a robot model");
  joint_values_.assign(model_->joints().size(), 0.0);
  link_transforms_.assign(model_->links().size(), Eigen::Isometry3d::Identity());
  positions_ = model_->defaultPositions();
  update();
}

void RobotState::setPositions(const Eigen::VectorXd& positions) {
  if (static_cast<size_t>(positions.size()) != model_->variableCount()) {
    throw std::invalid_argument("RobotState::setPositions: " + std::to_string(positions.size()) + " values for " +
                                std::to_string(model_->variableCount()) + " variables");
  }
  if (!positions.allFinite()) throw std::invalid_argument("RobotState::setPositions: non-finite joint value");
  positions_ = positions;
  update();
}

double RobotState::jointPosition(const std::string& joint) const {
  const int index = model_->jointIndex(joint);
  if (index < 0) throw std::invalid_argument("unknown joint '" + joint + "'");
  return joint_values_[index];
}

void RobotState::setJointPosition(const std::string& joint, double value) {
  const int index = model_->jointIndex(joint);
  if (index < 0) throw std::invalid_argument("unknown joint '" + joint + "'");
  const JointModel& model = model_->joints()[index];
  if (!model.isActive()) throw std::invalid_argument("joint '" + joint + "' is fixed or a mimic joint");
  if (!std::isfinite(value)) throw std::invalid_argument("non-finite value for joint '" + joint + "'");
  positions_[model.variable_index] = value;
  update();
}

Eigen::VectorXd RobotState::groupPositions(const std::string& group) const {
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  Eigen::VectorXd values(g->active_joints.size());
  for (size_t i = 0; i < g->active_joints.size(); ++i) {
    values[i] = positions_[model_->joint(g->active_joints[i]).variable_index];
  }
  return values;
}

void RobotState::setGroupPositions(const std::string& group, const Eigen::VectorXd& values) {
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  if (static_cast<size_t>(values.size()) != g->active_joints.size()) {
    throw std::invalid_argument("group '" + group + "' has " + std::to_string(g->active_joints.size()) +
                                " variables, got " + std::to_string(values.size()) + " values");
  }
  if (!values.allFinite()) throw std::invalid_argument("non-finite value for group '" + group + "'");
  for (size_t i = 0; i < g->active_joints.size(); ++i) {
    positions_[model_->joint(g->active_joints[i]).variable_index] = values[i];
  }
  update();
}

void RobotState::setVariablePositions(const std::vector<int>& indices, const Eigen::VectorXd& values) {
  if (static_cast<size_t>(values.size()) != indices.size()) {
    throw std::invalid_argument("RobotState::setVariablePositions: " + std::to_string(values.size()) +
                                " values for " + std::to_string(indices.size()) + " indices");
  }
  if (!values.allFinite()) throw std::invalid_argument("RobotState::setVariablePositions: non-finite value");
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < 0 || indices[i] >= positions_.size()) {
      throw std::invalid_argument("RobotState::setVariablePositions: variable index " + std::to_string(indices[i]) +
                                  " out of range");
    }
    positions_[indices[i]] = values[i];
  }
  update();
}

bool RobotState::setToNamedState(const std::string& group, const std::string& state) {
  const GroupState* s = model_->findGroupState(group, state);
  if (!s) return false;
  for (const auto& [joint, value] : s->values) {
    const JointModel& model = model_->joint(joint);
    // Values of mimic joints in a state follow from their source joint.
    if (model.isActive()) positions_[model.variable_index] = value;
  }
  update();
  return true;
}

const Eigen::Isometry3d& RobotState::linkTransform(const std::string& link) const {
  const int index = model_->linkIndex(link);
  if (index < 0) throw std::out_of_range("unknown link '" + link + "'");
  return link_transforms_[index];
}

bool RobotState::satisfiesBounds(double tolerance) const {
  for (size_t v = 0; v < model_->variableCount(); ++v) {
    const auto& limits = model_->variableJoint(v).limits;
    if (!limits.bounded) continue;
    if (positions_[v] < limits.lower - tolerance || positions_[v] > limits.upper + tolerance) return false;
  }
  return true;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> RobotState::jacobian(const std::string& group, const std::string& link,
                                                              const Eigen::Vector3d& reference_point) const {
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  const Eigen::Vector3d point = linkTransform(link) * reference_point;
  // Column of each model variable in the group (-1: not in the group).
  std::vector<int> column(model_->variableCount(), -1);
  for (size_t i = 0; i < g->active_joints.size(); ++i) column[model_->joint(g->active_joints[i]).variable_index] = i;
  Eigen::Matrix<double, 6, Eigen::Dynamic> result =
      Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, static_cast<Eigen::Index>(g->active_joints.size()));
  const auto& joints = model_->joints();
  for (int l = model_->linkIndex(link); l > 0; l = model_->links()[l].parent_link) {
    const JointModel& joint = joints[model_->links()[l].parent_joint];
    if (joint.type == JointType::kFixed) continue;
    int variable = joint.variable_index;
    double scale = 1.0;
    if (joint.mimic) {
      variable = joints[joint.mimic->joint_index].variable_index;
      scale = joint.mimic->multiplier;
    }
    if (variable < 0 || column[variable] < 0) continue;
    // The joint frame is the child link's frame; the axis is given in it.
    const Eigen::Isometry3d& frame = link_transforms_[l];
    const Eigen::Vector3d axis = frame.linear() * joint.axis;
    auto col = result.col(column[variable]);
    if (joint.type == JointType::kPrismatic) {
      col.head<3>() += scale * axis;
    } else {
      col.head<3>() += scale * axis.cross(point - frame.translation());
      col.tail<3>() += scale * axis;
    }
  }
  return result;
}

void RobotState::update() {
  const auto& joints = model_->joints();
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].isActive()) joint_values_[j] = positions_[joints[j].variable_index];
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].mimic) {
      const auto& mimic = *joints[j].mimic;
      joint_values_[j] = mimic.multiplier * joint_values_[mimic.joint_index] + mimic.offset;
    }
  }
  const auto& links = model_->links();
  link_transforms_[0] = Eigen::Isometry3d::Identity();
  for (size_t l = 1; l < links.size(); ++l) {
    const JointModel& joint = joints[links[l].parent_joint];
    const Eigen::Isometry3d& parent = link_transforms_[links[l].parent_link];
    Eigen::Isometry3d& t = link_transforms_[l];
    // Most joint origins are pure offsets: then the product is the parent's rotation and a moved origin.
    if (isIdentityRotation(joint.origin.linear())) {
      t.linear() = parent.linear();
      t.translation() = parent * joint.origin.translation();
    } else {
      t = parent * joint.origin;
    }
    const double value = joint_values_[links[l].parent_joint];
    switch (joint.type) {
      case JointType::kRevolute:
      case JointType::kContinuous:
        rotate(&t, joint.axis, value);
        break;
      case JointType::kPrismatic:
        t.translation() += t.linear() * (value * joint.axis);
        break;
      case JointType::kFixed:
        break;
    }
  }
}

}  // namespace sixdof_core
