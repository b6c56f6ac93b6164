#include "sixdof_planning/move_group_context.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <moveit_msgs/DisplayTrajectory.h>
#include <moveit_msgs/PlanningSceneComponents.h>
#include <sixdof_core/time_parameterization.h>
#include <sixdof_msgs/ErrorReport.h>
#include <visualization_msgs/MarkerArray.h>

#include "sixdof_planning/conversions.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {

// Mimic joints given in a request must agree with their source joint to this tolerance.
// A mimic joint is derived from its source joint; a measured state may differ by the coupling's compliance
// (a squeezing simulated gripper reads ~1e-4 m apart), but not contradict the relation.
constexpr double kMimicTolerance = 2e-3;

}  // namespace

MoveGroupContext::MoveGroupContext(ros::NodeHandle nh, MoveGroupConfig config)
    : nh_(std::move(nh)), config_(std::move(config)) {
  const char* package_path = std::getenv("ROS_PACKAGE_PATH");
  try {
    model_ = std::make_shared<const sixdof_core::RobotModel>(
        config_.urdf, config_.srdf, sixdof_core::PackageResolver::fromRosPackagePath(package_path ? package_path : ""));
  } catch (const std::exception& e) {
    throw ConfigError(std::string("robot_description / robot_description_semantic: ") + e.what());
  }
  checkConfig(*model_, &config_);
  for (const auto& entry : config_.kinematics) {
    try {
      ik_solvers_[entry.first] = sixdof_core::createIkSolver(entry.second.solver, *model_, entry.first);
    } catch (const std::exception& e) {
      throw ConfigError("robot_description_kinematics/" + entry.first + ": " + e.what());
    }
  }
  try {
    scene_ = std::make_shared<const SceneStore>(model_, config_.default_robot_padding);
  } catch (const std::exception& e) {
    throw ConfigError(std::string("collision geometry of robot_description: ") + e.what());
  }
  state_monitor_ = std::make_unique<CurrentStateMonitor>(nh_, model_, "joint_states");
  // Not latched by roscpp: sendLastDisplayTrajectory gives a new subscriber the last trajectory.
  display_path_pub_ = nh_.advertise<moveit_msgs::DisplayTrajectory>(
      "move_group/display_planned_path", 1,
      [this](const ros::SingleSubscriberPublisher& subscriber) { sendLastDisplayTrajectory(subscriber); });
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("move_group/planning_scene_markers", 1, true);
  monitored_scene_pub_ = nh_.advertise<moveit_msgs::PlanningScene>("move_group/monitored_planning_scene", 1, true);
  error_reports_pub_ = nh_.advertise<sixdof_msgs::ErrorReport>("move_group/error_reports", 100);
  publishScene();
}

std::shared_ptr<const sixdof_core::IkSolver> MoveGroupContext::ikSolver(const std::string& group) const {
  auto it = ik_solvers_.find(group);
  return it == ik_solvers_.end() ? nullptr : it->second;
}

sixdof_core::IkOptions MoveGroupContext::ikOptions(const std::string& group) const {
  sixdof_core::IkOptions options;
  auto it = config_.kinematics.find(group);
  if (it != config_.kinematics.end()) {
    options.timeout = it->second.timeout * it->second.attempts;
    options.position_only = it->second.position_only;
  }
  return options;
}

void MoveGroupContext::waitForCurrentState() const {
  // The current state is the robot's at the time of the request: wait (up to 1 s of wall time, MoveIt's bound) for
  // joint_states stamped at or after now. On timeout the last state is used; its staleness is judged as before.
  const ros::Time now = ros::Time::now();
  if (!now.isZero()) state_monitor_->waitForStateNewerThan(now, 1.0);
}

ErrorCode MoveGroupContext::currentState(const std::string& source, sixdof_core::RobotState* state) const {
  waitForCurrentState();
  std::vector<std::string> missing;
  if (!state_monitor_->currentState(config_.joint_state_timeout, state, &missing)) {
    return makeError(ErrorCode::ROBOT_STATE_STALE, "no joint_states received for joints " + joinNames(missing),
                     source);
  }
  warnIfStale(source);
  return makeSuccess(source);
}

ErrorCode MoveGroupContext::resolveRobotState(const moveit_msgs::RobotState& msg, const std::string& what,
                                              const std::string& source, sixdof_core::RobotState* state,
                                              std::shared_ptr<const SceneStore>* scene,
                                              std::shared_ptr<const SceneStore> base_scene) const {
  if (!msg.multi_dof_joint_state.joint_names.empty()) {
    return makeError(ErrorCode::INVALID_ROBOT_STATE,
                     what + ".multi_dof_joint_state sets joints (" + joinNames(msg.multi_dof_joint_state.joint_names) +
                         "): multi-DOF joints are not supported (the robot model has none)",
                     source);
  }
  const auto& joint_state = msg.joint_state;
  ErrorCode code = validateJointState(*model_, joint_state, source);
  if (!isSuccess(code)) {
    code.message = what + ": " + code.message;
    return code;
  }
  size_t active_given = 0;
  for (const auto& name : joint_state.name) active_given += model_->joint(name).isActive() ? 1 : 0;
  if (active_given < model_->variableCount()) {
    waitForCurrentState();
    std::vector<std::string> missing;
    if (!state_monitor_->currentState(config_.joint_state_timeout, state, &missing)) {
      std::vector<std::string> needed;
      for (const auto& name : missing) {
        if (std::find(joint_state.name.begin(), joint_state.name.end(), name) == joint_state.name.end()) {
          needed.push_back(name);
        }
      }
      if (!needed.empty()) {
        return makeError(ErrorCode::ROBOT_STATE_STALE,
                         what + " does not set joints " + joinNames(needed) +
                             " and no joint_states were received for them",
                         source);
      }
    }
    warnIfStale(source);
  }
  // The given joints' values, set at once (one forward kinematics update for them all).
  std::vector<int> variables;
  Eigen::VectorXd values(static_cast<Eigen::Index>(joint_state.name.size()));
  for (size_t i = 0; i < joint_state.name.size(); ++i) {
    const int variable = model_->joint(joint_state.name[i]).variable_index;
    if (variable < 0) continue;  // a mimic joint: checked against its source below
    values[static_cast<Eigen::Index>(variables.size())] = joint_state.position[i];
    variables.push_back(variable);
  }
  values.conservativeResize(static_cast<Eigen::Index>(variables.size()));
  state->setVariablePositions(variables, values);
  for (size_t i = 0; i < joint_state.name.size(); ++i) {
    const double derived = state->jointPosition(joint_state.name[i]);
    if (std::abs(derived - joint_state.position[i]) > kMimicTolerance) {
      return makeError(ErrorCode::INVALID_ROBOT_STATE,
                       what + ": mimic joint '" + joint_state.name[i] + "' is " +
                           std::to_string(joint_state.position[i]) +
                           " but its source joint puts it at " + std::to_string(derived),
                       source);
    }
  }
  *scene = base_scene ? base_scene : this->scene();
  // As MoveIt: a full state (is_diff false) carries exactly the robot's attached objects, a diff adds to them.
  if (!msg.attached_collision_objects.empty() || (!msg.is_diff && !(*scene)->attachedObjects().empty())) {
    auto copy = std::make_shared<SceneStore>(**scene);
    if (!msg.is_diff) copy->clearAttachedObjects();
    for (size_t i = 0; i < msg.attached_collision_objects.size(); ++i) {
      code = copy->applyAttachedObject(msg.attached_collision_objects[i], *state, source);
      if (!isSuccess(code)) {
        code.message = what + ".attached_collision_objects[" + std::to_string(i) + "]: " + code.message;
        return recode(code, ErrorCode::INVALID_ROBOT_STATE);
      }
    }
    *scene = copy;
  }
  return makeSuccess(source);
}

void MoveGroupContext::warnIfStale(const std::string& source) const {
  const double age = state_monitor_->liveness().joint_states_age;
  if (age > config_.joint_state_timeout) {
    ROS_WARN_STREAM_THROTTLE(5.0, source << ": joint_states stale for " << std::round(age * 10.0) / 10.0
                                         << " s: using the last known robot state");
  }
}

std::shared_ptr<const SceneStore> MoveGroupContext::scene() const {
  std::lock_guard<std::mutex> lock(scene_mutex_);
  return scene_;
}

ErrorCode MoveGroupContext::applyScene(const moveit_msgs::PlanningScene& msg, const std::string& source) {
  sixdof_core::RobotState state(model_);
  // Attached objects and objects given in link frames are placed at the current state; objects in the planning
  // frame need none, so the scene can be set up before the robot publishes joint_states.
  bool needs_state = !msg.robot_state.attached_collision_objects.empty();
  for (const auto& object : msg.world.collision_objects) {
    const std::string& frame = object.header.frame_id;
    needs_state = needs_state || (model_->linkIndex(frame) >= 0 && frame != planningFrame());
  }
  ErrorCode code = makeSuccess(source);
  if (needs_state) {
    code = currentState(source, &state);
    if (!isSuccess(code)) return code;
  }
  {
    // One writer at a time; readers keep using the old scene until the swap.
    std::lock_guard<std::mutex> lock(scene_mutex_);
    auto copy = std::make_shared<SceneStore>(*scene_);
    code = copy->apply(msg, state, source);
    if (!isSuccess(code)) return code;
    scene_ = copy;
  }
  publishScene();
  return makeSuccess(source);
}

moveit_msgs::PlanningScene MoveGroupContext::sceneMessage(uint32_t components, const std::string& source) const {
  using C = moveit_msgs::PlanningSceneComponents;
  const auto store = scene();
  moveit_msgs::PlanningScene msg;
  msg.name = "move_group";
  msg.robot_model_name = model_->name();
  msg.is_diff = false;
  if (components & C::ROBOT_STATE) {
    sixdof_core::RobotState state(model_);
    // The scene has objects even before joint_states arrive; the joint values are then left empty.
    if (isSuccess(currentState(source, &state))) msg.robot_state.joint_state = toJointState(state);
  }
  if (components & C::ROBOT_STATE_ATTACHED_OBJECTS) msg.robot_state.attached_collision_objects = store->attachedObjects();
  if (components & (C::WORLD_OBJECT_NAMES | C::WORLD_OBJECT_GEOMETRY)) {
    msg.world.collision_objects = store->worldObjects();
    if (!(components & C::WORLD_OBJECT_GEOMETRY)) {
      for (auto& object : msg.world.collision_objects) {
        moveit_msgs::CollisionObject named;
        named.header = object.header;
        named.id = object.id;
        named.type = object.type;
        named.operation = object.operation;
        object = named;
      }
    }
  }
  if (components & C::OCTOMAP) store->octomapMessage(&msg.world.octomap);
  if (components & C::TRANSFORMS) {
    // MoveIt's fixed frames: the planning frame itself (the scene knows no other frames).
    geometry_msgs::TransformStamped identity;
    identity.header.frame_id = planningFrame();
    identity.child_frame_id = planningFrame();
    identity.transform.rotation.w = 1.0;
    msg.fixed_frame_transforms.push_back(identity);
  }
  if (components & C::ALLOWED_COLLISION_MATRIX) msg.allowed_collision_matrix = store->allowedCollisionMatrix();
  if (components & C::LINK_PADDING_AND_SCALING) {
    for (const auto& link : model_->links()) {
      moveit_msgs::LinkPadding padding;
      padding.link_name = link.name;
      padding.padding = config_.default_robot_padding;
      msg.link_padding.push_back(padding);
      moveit_msgs::LinkScale scale;
      scale.link_name = link.name;
      scale.scale = 1.0;
      msg.link_scale.push_back(scale);
    }
  }
  if (components & C::OBJECT_COLORS) msg.object_colors = store->objectColors();
  return msg;
}

void MoveGroupContext::reportError(const std::string& caller, const std::string& interface, const ErrorCode& code) {
  ROS_WARN_STREAM(interface << " (from " << caller << "): " << errorCodeName(code.val) << ": " << code.message);
  sixdof_msgs::ErrorReport report;
  report.header.stamp = ros::Time::now();
  report.caller_id = caller;
  report.interface = interface;
  report.error_code = code;
  report.message = code.message;
  report.source = code.source;
  error_reports_pub_.publish(report);
}

void MoveGroupContext::setOccupancyMap(std::shared_ptr<const sixdof_core::OccupancyMap> map,
                                       const Eigen::Isometry3d& map_pose) {
  std::lock_guard<std::mutex> lock(scene_mutex_);
  auto copy = std::make_shared<SceneStore>(*scene_);
  copy->setOccupancyMap(std::move(map), map_pose);
  scene_ = copy;
}

ErrorCode MoveGroupContext::linkInTip(const std::string& group, const std::string& link, const std::string& source,
                                      Eigen::Isometry3d* link_in_tip) const {
  const auto solver = ikSolver(group);
  if (!solver) {
    return makeError(ErrorCode::NO_IK_SOLUTION,
                     "group '" + group + "' has no IK solver (no entry in robot_description_kinematics)", source);
  }
  const std::string& tip = solver->chain().tipLink();
  *link_in_tip = Eigen::Isometry3d::Identity();
  if (link.empty() || link == tip) return makeSuccess(source);
  ErrorCode code = validateLink(*model_, link, source);
  if (!isSuccess(code)) return code;
  // Walk up from the link: only fixed joints may separate it from the tip.
  int index = model_->linkIndex(link);
  while (index >= 0 && model_->links()[index].name != tip) {
    const auto& parent_joint = model_->joints()[model_->links()[index].parent_joint];
    if (parent_joint.type != sixdof_core::JointType::kFixed) break;
    *link_in_tip = parent_joint.origin * *link_in_tip;
    index = model_->links()[index].parent_link;
  }
  if (index < 0 || model_->links()[index].name != tip) {
    return makeError(ErrorCode::INVALID_LINK_NAME,
                     "link '" + link + "' is neither the tip link '" + tip + "' of group '" + group +
                         "' nor rigidly fixed to it",
                     source);
  }
  return makeSuccess(source);
}

ErrorCode MoveGroupContext::timeParameterize(const std::vector<std::string>& joints,
                                             const std::vector<Eigen::VectorXd>& path, double velocity_scaling,
                                             double acceleration_scaling, const std::string& source,
                                             sixdof_core::Trajectory* trajectory, double sample_period) const {
  sixdof_core::TimeParameterizationOptions options;
  for (const auto& joint : joints) {
    const auto& limits = config_.joint_limits.at(joint);
    options.max_velocity.push_back(limits.max_velocity);
    options.max_acceleration.push_back(limits.max_acceleration);
  }
  options.velocity_scaling = velocity_scaling;
  options.acceleration_scaling = acceleration_scaling;
  options.sample_period = sample_period;
  std::vector<std::vector<double>> waypoints;
  for (const auto& q : path) waypoints.emplace_back(q.data(), q.data() + q.size());
  auto result = sixdof_core::computeTimeOptimalTrajectory(joints, waypoints, options);
  if (!result.ok()) {
    return makeError(ErrorCode::PLANNING_FAILED, "time parameterization failed: " + result.message, source);
  }
  *trajectory = std::move(result.trajectory);
  return makeSuccess(source);
}

namespace {

moveit_msgs::DisplayTrajectoryConstPtr displayMessage(const std::string& model, const std::string& frame,
                                                      const sixdof_core::RobotState& start,
                                                      const sixdof_core::Trajectory& trajectory) {
  auto msg = boost::make_shared<moveit_msgs::DisplayTrajectory>();
  msg->model_id = model;
  msg->trajectory.resize(1);
  msg->trajectory[0].joint_trajectory = toJointTrajectory(trajectory);
  msg->trajectory[0].joint_trajectory.header.frame_id = frame;
  msg->trajectory_start.joint_state = toJointState(start);
  return msg;
}

}  // namespace

void MoveGroupContext::publishDisplayTrajectory(const sixdof_core::RobotState& start,
                                                sixdof_core::Trajectory trajectory) {
  std::lock_guard<std::mutex> lock(display_mutex_);
  if (display_path_pub_.getNumSubscribers() == 0) {
    display_msg_.reset();
    display_start_ = std::make_unique<sixdof_core::RobotState>(start);
    display_trajectory_ = std::move(trajectory);
    return;
  }
  display_start_.reset();
  display_msg_ = displayMessage(model_->name(), planningFrame(), start, trajectory);
  display_path_pub_.publish(display_msg_);
}

void MoveGroupContext::sendLastDisplayTrajectory(const ros::SingleSubscriberPublisher& subscriber) {
  std::lock_guard<std::mutex> lock(display_mutex_);
  if (!display_msg_ && display_start_) {
    display_msg_ = displayMessage(model_->name(), planningFrame(), *display_start_, display_trajectory_);
    display_start_.reset();
    display_trajectory_ = sixdof_core::Trajectory();
  }
  if (display_msg_) subscriber.publish(*display_msg_);
}

void MoveGroupContext::publishScene() {
  using C = moveit_msgs::PlanningSceneComponents;
  markers_pub_.publish(scene()->markers());
  monitored_scene_pub_.publish(sceneMessage(C::SCENE_SETTINGS | C::ROBOT_STATE_ATTACHED_OBJECTS |
                                                C::WORLD_OBJECT_GEOMETRY | C::OBJECT_COLORS,
                                            "monitored_planning_scene"));
}

}  // namespace sixdof_planning
