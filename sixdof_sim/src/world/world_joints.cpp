#include <charconv>

#include "world_impl.h"

namespace sixdof_sim {
namespace {

// `digits` significant digits, or (0) the shortest text that reads back as the same double.
std::string number(double value, int digits = 0) {
  char text[32];
  const auto end = digits > 0 ? std::to_chars(text, text + sizeof text, value, std::chars_format::general, digits).ptr
                              : std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

// "<value> outside [<lower>, <upper>] (by <excess>)", exact: a value a rounding error past a limit shows as such.
std::string outsideLimits(const JointInfo& info, double value) {
  const double excess = value < info.lower ? info.lower - value : value - info.upper;
  const std::string limits = "[" + number(info.lower) + ", " + number(info.upper) + "]";
  return number(value) + " outside " + limits + " (by " + number(excess, 2) + ")";
}

}  // namespace

bool World::Impl::linkWorldPose(const std::string& link, Eigen::Isometry3d* pose) const {
  const auto it = links.find(link);
  if (it == links.end()) return false;
  *pose = toEigen(bodyWorld(it->second.body)) * it->second.body_to_link;
  return true;
}

const sixdof_core::RobotModel& World::robotModel() const { return *impl_->model; }

const sixdof_core::PackageResolver& World::packageResolver() const { return impl_->resolver; }

const std::vector<JointInfo>& World::joints() const { return impl_->joint_infos; }

std::vector<std::string> World::jointNames() const {
  std::vector<std::string> names;
  for (const JointInfo& info : impl_->joint_infos) names.push_back(info.name);
  return names;
}

int World::jointIndex(const std::string& name) const {
  const auto it = impl_->joint_index.find(name);
  return it == impl_->joint_index.end() ? -1 : it->second;
}

std::vector<double> World::initialJointPositions() const { return impl_->initial_positions; }

std::vector<double> World::jointPositions() const {
  std::vector<double> q;
  for (const JointRuntime& j : impl_->joints) {
    q.push_back(impl_->multibody->getJointPos(impl_->bodies[j.body].bullet_link));
  }
  return q;
}

std::vector<double> World::jointVelocities() const {
  std::vector<double> v;
  for (const JointRuntime& j : impl_->joints) {
    v.push_back(impl_->multibody->getJointVel(impl_->bodies[j.body].bullet_link));
  }
  return v;
}

std::vector<double> World::jointEfforts() const {
  std::vector<double> e;
  for (const JointRuntime& j : impl_->joints) e.push_back(j.applied_effort);
  return e;
}

Result World::setJointPositions(const std::vector<std::string>& names, const std::vector<double>& positions) {
  Impl& d = *impl_;
  if (names.size() != positions.size()) {
    return {Status::kInvalidArgument, "setJointPositions: " + std::to_string(names.size()) + " names but " +
                                          std::to_string(positions.size()) + " positions"};
  }
  std::vector<double> q = jointPositions();
  std::vector<bool> given(q.size(), false);
  for (size_t i = 0; i < names.size(); ++i) {
    const int j = jointIndex(names[i]);
    if (j < 0) return {Status::kUnknownJoint, "unknown joint '" + names[i] + "'"};
    if (!std::isfinite(positions[i])) {
      return {Status::kInvalidArgument, "joint '" + names[i] + "': position is not finite"};
    }
    const JointInfo& info = d.joint_infos[j];
    if (!info.withinLimits(positions[i])) {
      return {Status::kOutOfLimits, "joint '" + names[i] + "': position " + outsideLimits(info, positions[i])};
    }
    q[j] = positions[i];
    given[j] = true;
  }
  for (size_t j = 0; j < q.size(); ++j) {
    const int master = d.joints[j].master;
    if (master < 0) continue;
    const JointInfo& info = d.joint_infos[j];
    const double expected = info.mimic_multiplier * q[master] + info.mimic_offset;
    if (given[j] && std::abs(q[j] - expected) > 1e-6) {
      return {Status::kMimicJoint, "joint '" + info.name + "' mimics '" + info.mimic_of + "': expected " +
                                       std::to_string(expected) + ", got " + std::to_string(q[j])};
    }
    q[j] = expected;
  }
  // An attached object moves with the palm.
  std::optional<btTransform> palm_to_object;
  ObjectRuntime* attached = nullptr;
  int palm_body = 0;
  if (d.grasp_fix && !d.grasp_fix->attached().empty()) {
    attached = d.findObject(d.grasp_fix->attached());
    palm_body = d.links.at(d.grasp_config->palm_link).body;
    if (attached != nullptr) palm_to_object = d.bodyWorld(palm_body).inverse() * attached->body->getWorldTransform();
  }
  for (size_t j = 0; j < q.size(); ++j) {
    JointRuntime& runtime = d.joints[j];
    const int link = d.bodies[runtime.body].bullet_link;
    d.multibody->setJointPos(link, q[j]);
    d.multibody->setJointVel(link, 0.0);
    runtime.mode = JointControlMode::kPosition;
    runtime.target_position = q[j];
    runtime.target_velocity = 0.0;
    runtime.max_effort = d.joint_infos[j].max_effort;
  }
  d.refreshKinematics();
  if (attached != nullptr && palm_to_object) {
    attached->body->setWorldTransform(d.bodyWorld(palm_body) * *palm_to_object);
    attached->body->setLinearVelocity(btVector3(0, 0, 0));
    attached->body->setAngularVelocity(btVector3(0, 0, 0));
  }
  return Result::success();
}

Result World::Impl::checkJointCommand(const std::string& joint, int* index) {
  const auto it = joint_index.find(joint);
  if (it == joint_index.end()) return {Status::kUnknownJoint, "unknown joint '" + joint + "'"};
  *index = it->second;
  if (joints[*index].master >= 0) {
    return {Status::kMimicJoint,
            "joint '" + joint + "' mimics '" + joint_infos[*index].mimic_of + "': command '" +
                joint_infos[*index].mimic_of + "'"};
  }
  return Result::success();
}

namespace {
Result checkEffortBound(const JointInfo& info, double max_effort, double* bound) {
  if (!std::isfinite(max_effort) || max_effort < 0.0) {
    return {Status::kInvalidArgument, "joint '" + info.name + "': max_effort must be >= 0"};
  }
  if (max_effort > info.max_effort) {
    return {Status::kOutOfLimits, "joint '" + info.name + "': max_effort " + std::to_string(max_effort) +
                                      " above the URDF effort limit " + std::to_string(info.max_effort)};
  }
  *bound = max_effort > 0.0 ? max_effort : info.max_effort;
  return Result::success();
}
}  // namespace

Result World::setPositionTarget(const std::string& joint, double position, double velocity, double max_effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  const JointInfo& info = impl_->joint_infos[j];
  if (!std::isfinite(position) || !std::isfinite(velocity)) {
    return {Status::kInvalidArgument, "joint '" + joint + "': target is not finite"};
  }
  if (!info.withinLimits(position)) {
    return {Status::kOutOfLimits, "joint '" + joint + "': target " + outsideLimits(info, position)};
  }
  double bound = 0.0;
  r = checkEffortBound(info, max_effort, &bound);
  if (!r.ok()) return r;
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kPosition;
  runtime.target_position = position;
  runtime.target_velocity = velocity;
  runtime.max_effort = bound;
  return Result::success();
}

Result World::setVelocityTarget(const std::string& joint, double velocity, double max_effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  if (!std::isfinite(velocity)) return {Status::kInvalidArgument, "joint '" + joint + "': velocity is not finite"};
  double bound = 0.0;
  r = checkEffortBound(impl_->joint_infos[j], max_effort, &bound);
  if (!r.ok()) return r;
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kVelocity;
  runtime.target_velocity = velocity;
  runtime.max_effort = bound;
  return Result::success();
}

Result World::setEffort(const std::string& joint, double effort) {
  int j = 0;
  Result r = impl_->checkJointCommand(joint, &j);
  if (!r.ok()) return r;
  const JointInfo& info = impl_->joint_infos[j];
  if (!std::isfinite(effort)) return {Status::kInvalidArgument, "joint '" + joint + "': effort is not finite"};
  if (std::abs(effort) > info.max_effort) {
    return {Status::kOutOfLimits, "joint '" + joint + "': |effort| " + std::to_string(std::abs(effort)) +
                                      " above the URDF effort limit " + std::to_string(info.max_effort)};
  }
  JointRuntime& runtime = impl_->joints[j];
  runtime.mode = JointControlMode::kEffort;
  runtime.effort = effort;
  return Result::success();
}

std::optional<JointControlMode> World::controlMode(const std::string& joint) const {
  const int j = jointIndex(joint);
  if (j < 0) return std::nullopt;
  const JointRuntime& runtime = impl_->joints[j];
  return runtime.master >= 0 ? impl_->joints[runtime.master].mode : runtime.mode;
}

std::vector<std::string> World::linkNames() const { return impl_->link_order; }

Result World::linkPose(const std::string& link, Eigen::Isometry3d* pose) const {
  if (!impl_->linkWorldPose(link, pose)) return {Status::kUnknownLink, "unknown link '" + link + "'"};
  return Result::success();
}

}  // namespace sixdof_sim
