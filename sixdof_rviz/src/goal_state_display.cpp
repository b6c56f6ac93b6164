#include "goal_state_display.h"

#include <algorithm>
#include <cmath>

#include <OgreAxisAlignedBox.h>
#include <OgreMesh.h>
#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <rviz/default_plugin/interactive_markers/interactive_marker.h>
#include <rviz/mesh_loader.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/InteractiveMarker.h>

#include "ghost_robot.h"
#include "sixdof_rviz/planning_panel_logic.h"

namespace sixdof_rviz {
namespace {

visualization_msgs::InteractiveMarkerControl axisControl(const std::string& name, double w, double x, double y,
                                                         double z, uint8_t mode) {
  visualization_msgs::InteractiveMarkerControl control;
  control.name = name;
  control.orientation.w = w;
  control.orientation.x = x;
  control.orientation.y = y;
  control.orientation.z = z;
  control.orientation_mode = visualization_msgs::InteractiveMarkerControl::INHERIT;
  control.interaction_mode = mode;
  return control;
}

// Bounding box of one URDF visual geometry, in its link's frame; empty when a mesh cannot be loaded.
Eigen::AlignedBox3d visualBounds(const urdf::Visual& visual) {
  Eigen::AlignedBox3d local;
  switch (visual.geometry->type) {
    case urdf::Geometry::SPHERE: {
      const double r = static_cast<const urdf::Sphere&>(*visual.geometry).radius;
      local.extend(Eigen::Vector3d(-r, -r, -r)).extend(Eigen::Vector3d(r, r, r));
      break;
    }
    case urdf::Geometry::BOX: {
      const urdf::Vector3& d = static_cast<const urdf::Box&>(*visual.geometry).dim;
      const Eigen::Vector3d half(d.x / 2, d.y / 2, d.z / 2);
      local.extend(-half).extend(half);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*visual.geometry);
      const Eigen::Vector3d half(cylinder.radius, cylinder.radius, cylinder.length / 2);
      local.extend(-half).extend(half);
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*visual.geometry);
      const Ogre::MeshPtr ogre_mesh = rviz::loadMeshFromResource(mesh.filename);
      if (ogre_mesh.isNull()) return local;
      const Ogre::AxisAlignedBox& box = ogre_mesh->getBounds();
      const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      local.extend(Eigen::Vector3d(box.getMinimum().x, box.getMinimum().y, box.getMinimum().z).cwiseProduct(scale))
          .extend(Eigen::Vector3d(box.getMaximum().x, box.getMaximum().y, box.getMaximum().z).cwiseProduct(scale));
      break;
    }
  }
  const urdf::Pose& origin = visual.origin;
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translate(Eigen::Vector3d(origin.position.x, origin.position.y, origin.position.z));
  transform.rotate(Eigen::Quaterniond(origin.rotation.w, origin.rotation.x, origin.rotation.y, origin.rotation.z));
  Eigen::AlignedBox3d out;
  for (int corner = 0; corner < 8; ++corner) {
    out.extend(transform * local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  }
  return out;
}

// Extends `box` (in the tip link's frame) by the visuals of `link` and every link below it: the end effector.
bool extendByVisuals(const urdf::Link& link, const Eigen::Isometry3d& tip_from_root, const LinkPoseMap& poses,
                     Eigen::AlignedBox3d* box, std::string* bad_mesh) {
  const Eigen::Isometry3d tip_from_link = tip_from_root * poses.at(link.name);
  for (const auto& visual : link.visual_array) {
    if (!visual || !visual->geometry) continue;
    const Eigen::AlignedBox3d bounds = visualBounds(*visual);
    if (bounds.isEmpty()) {
      *bad_mesh = static_cast<const urdf::Mesh&>(*visual->geometry).filename;
      return false;
    }
    for (int corner = 0; corner < 8; ++corner) {
      box->extend(tip_from_link * bounds.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
    }
  }
  for (const auto& child : link.child_links) {
    if (!extendByVisuals(*child, tip_from_root, poses, box, bad_mesh)) return false;
  }
  return true;
}

// The group the marker serves when none is configured: the SRDF's first chain group (the marker needs a tip link).
std::string defaultChainGroup(const SemanticModel& model) {
  for (const PlanningGroup& group : model.groups()) {
    if (!group.tip_link.empty()) return group.name;
  }
  return "";
}

sensor_msgs::JointState toJointState(const JointValues& values) {
  sensor_msgs::JointState msg;
  for (const auto& [name, value] : values) {
    msg.name.push_back(name);
    msg.position.push_back(value);
  }
  return msg;
}

}  // namespace

GoalStateDisplay::GoalStateDisplay() {
  robot_description_property_ = new rviz::StringProperty(
      "Robot Description", "robot_description", "Parameter holding the URDF.", this, SLOT(loadModel()));
  semantic_description_property_ =
      new rviz::StringProperty("Semantic Description", "robot_description_semantic",
                               "Parameter holding the SRDF (planning groups).", this, SLOT(loadModel()));
  group_property_ = new rviz::StringProperty(
      "Planning Group", "",
      "SRDF chain group whose tip link carries the marker; empty: the SRDF's first chain group.",
      this, SLOT(loadModel()));
  joint_state_topic_property_ = new rviz::RosTopicProperty(
      "Joint State Topic", "joint_states", "sensor_msgs/JointState",
      "Current robot state: the start of dragging and the IK seed.", this, SLOT(updateJointStateTopic()));
  goal_pose_topic_property_ = new rviz::RosTopicProperty(
      "Goal Pose Topic", "sixdof_rviz/goal_pose", "geometry_msgs/PoseStamped",
      "Tip link poses (in the robot's root frame) that move the marker as if dragged there.", this,
      SLOT(updateGoalPoseTopic()));
  ik_rate_property_ =
      new rviz::FloatProperty("IK Rate", 10.0f, "Maximum compute_ik calls per second while dragging.", this);
  ik_rate_property_->setMin(0.5f);
  ik_rate_property_->setMax(100.0f);
  marker_scale_property_ = new rviz::FloatProperty(
      "Marker Scale", 1.0f,
      "Size of the interactive marker relative to the end effector (the tip link and the links below it): at 1 its "
      "rings just enclose the end effector's visual geometry.",
      this, SLOT(loadModel()));
  marker_scale_property_->setMin(0.1f);
  // Opaque enough that where the goal robot overlaps the arm (at the current state) its own colour shows, not a blend
  // with the arm's orange and grey materials.
  alpha_property_ =
      new rviz::FloatProperty("Robot Alpha", 0.8f, "Opacity of the goal robot.", this, SLOT(updateAppearance()));
  alpha_property_->setMin(0.0f);
  alpha_property_->setMax(1.0f);
  reachable_color_property_ = new rviz::ColorProperty("Reachable Color", QColor(0, 190, 255),
                                                      "Goal robot colour for a valid goal.", this,
                                                      SLOT(updateAppearance()));
  unreachable_color_property_ = new rviz::ColorProperty(
      "Unreachable Color", QColor(230, 0, 0), "Goal robot colour when there is no IK solution or it collides.", this,
      SLOT(updateAppearance()));
}

GoalStateDisplay::~GoalStateDisplay() { stopWorker(); }

void GoalStateDisplay::onInitialize() {
  goal_pub_ = update_nh_.advertise<sensor_msgs::JointState>(kGoalStateTopic, 1, true);
  ik_ = std::make_unique<GoalIk>(ros::NodeHandle());
  worker_ = std::thread(&GoalStateDisplay::ikLoop, this);
  loadModel();
}

void GoalStateDisplay::stopWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void GoalStateDisplay::loadModel() {
  if (context_ == nullptr) return;
  marker_.reset();
  robot_.reset();
  model_.reset();
  std::string urdf_xml;
  std::string srdf_xml;
  const std::string urdf_param = robot_description_property_->getStdString();
  const std::string srdf_param = semantic_description_property_->getStdString();
  if (!update_nh_.getParam(urdf_param, urdf_xml) || !update_nh_.getParam(srdf_param, srdf_xml)) {
    reportConfigError(this, "Robot",
                 "parameters '" + urdf_param + "' and '" + srdf_param + "' must be set");
    return;
  }
  try {
    model_ = std::make_shared<SemanticModel>(urdf_xml, srdf_xml);
  } catch (const std::invalid_argument& e) {
    reportConfigError(this, "Robot", e.what());
    return;
  }
  group_ = group_property_->getStdString().empty() ? defaultChainGroup(*model_) : group_property_->getStdString();
  const PlanningGroup* group = model_->group(group_);
  if (group == nullptr || group->tip_link.empty()) {
    reportConfigError(this, "Robot",
                 "planning group '" + group_ + "' is not a chain group of the SRDF (needed for its tip link)");
    model_.reset();
    return;
  }
  tip_link_ = group->tip_link;
  fk_ = std::make_shared<LinkPoses>(model_->robotModel());
  // Like MoveIt, the marker is sized from the end effector so that it is not hidden inside the gripper.
  {
    const LinkPoseMap poses = fk_->compute(JointValues{});
    end_effector_bounds_.setEmpty();
    std::string bad_mesh;
    if (!extendByVisuals(*model_->urdf()->getLink(tip_link_), poses.at(tip_link_).inverse(), poses,
                         &end_effector_bounds_, &bad_mesh)) {
      reportConfigError(this, "Robot", "cannot load the mesh '" + bad_mesh + "' of the end effector");
      model_.reset();
      return;
    }
    if (end_effector_bounds_.isEmpty()) {
      reportConfigError(this, "Robot", "tip link '" + tip_link_ + "' and the links below it have no visual geometry");
      model_.reset();
      return;
    }
  }
  robot_ = std::make_unique<GhostRobot>(scene_node_, context_, "Goal State", this, *model_->urdf(), fk_);
  setStatusStd(rviz::StatusProperty::Ok, "Robot", "group '" + group_ + "', tip link '" + tip_link_ + "'");
  // Until the current state is known the marker sits at the all-zero state and no goal is published.
  goal_.clear();
  for (const auto& [name, joint] : model_->urdf()->joints_) {
    if (joint->type != urdf::Joint::FIXED) goal_[name] = 0.0;
  }
  marker_on_current_state_ = false;
  reachable_ = true;
  robot_->setState(goal_);
  updateAppearance();
  robot_->setVisible(isEnabled());
  if (isEnabled()) createMarker();
  updateJointStateTopic();
  updateGoalPoseTopic();
}

void GoalStateDisplay::createMarker() {
  // The marker (and its drag sphere, which is always visible) exists only while the display is enabled: hiding the
  // display's scene node does not hide controls created after it was hidden.
  marker_ = std::make_unique<rviz::InteractiveMarker>(scene_node_, context_);
  connect(marker_.get(), &rviz::InteractiveMarker::userFeedback, this, &GoalStateDisplay::processFeedback);
  if (!marker_on_current_state_ && latest_joint_state_) {
    startFromCurrentState(*latest_joint_state_);
    return;
  }
  placeMarker();
  robot_->setState(goal_);
  if (!marker_on_current_state_) {
    setStatusStd(rviz::StatusProperty::Warn, "Goal", "waiting for the current state on joint_states");
  }
}

void GoalStateDisplay::startFromCurrentState(const sensor_msgs::JointState& state) {
  for (size_t i = 0; i < state.name.size() && i < state.position.size(); ++i) goal_[state.name[i]] = state.position[i];
  marker_on_current_state_ = true;
  placeMarker();
  showGoal(true);
  setStatusStd(rviz::StatusProperty::Ok, "Goal", "at the current state");
}

void GoalStateDisplay::placeMarker() {
  placeMarkerAt(tf2::toMsg(fk_->compute(goal_).at(tip_link_)));
}

void GoalStateDisplay::placeMarkerAt(const geometry_msgs::Pose& pose) {
  // The rings (diameter = scale) centred on the tip link enclose its farthest end-effector point.
  double reach = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    reach = std::max(reach,
                     end_effector_bounds_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)).norm());
  }
  const double scale = 2.0 * reach * marker_scale_property_->getFloat();
  visualization_msgs::InteractiveMarker msg;
  msg.header.frame_id = fk_->rootLink();
  msg.name = "goal_state";
  msg.description = "Goal of " + group_;
  msg.scale = scale;
  msg.pose = pose;
  using Control = visualization_msgs::InteractiveMarkerControl;
  const double s = std::sqrt(0.5);
  msg.controls.push_back(axisControl("rotate_x", s, s, 0, 0, Control::ROTATE_AXIS));
  msg.controls.push_back(axisControl("move_x", s, s, 0, 0, Control::MOVE_AXIS));
  msg.controls.push_back(axisControl("rotate_z", s, 0, s, 0, Control::ROTATE_AXIS));
  msg.controls.push_back(axisControl("move_z", s, 0, s, 0, Control::MOVE_AXIS));
  msg.controls.push_back(axisControl("rotate_y", s, 0, 0, s, Control::ROTATE_AXIS));
  msg.controls.push_back(axisControl("move_y", s, 0, 0, s, Control::MOVE_AXIS));
  // A sphere to drag the position freely in the view plane. At the tip link's origin it would be buried in the
  // wrist and the gripper: it sits just beyond the end effector, on the line from the tip link through the end
  // effector's centre (the approach direction).
  Control free = axisControl("move_3d", 1, 0, 0, 0, Control::MOVE_3D);
  visualization_msgs::Marker sphere;
  sphere.type = visualization_msgs::Marker::SPHERE;
  const double diameter = 0.2 * scale;
  sphere.scale.x = sphere.scale.y = sphere.scale.z = diameter;
  Eigen::Vector3d direction = end_effector_bounds_.center();
  direction = direction.norm() > 1e-9 ? direction.normalized() : Eigen::Vector3d::UnitZ();
  double extent = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    extent = std::max(
        extent, direction.dot(end_effector_bounds_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner))));
  }
  const Eigen::Vector3d centre = direction * (extent + diameter / 2);
  sphere.pose.position.x = centre.x();
  sphere.pose.position.y = centre.y();
  sphere.pose.position.z = centre.z();
  sphere.pose.orientation.w = 1.0;
  sphere.color.r = 0.9f;
  sphere.color.g = 0.9f;
  sphere.color.b = 0.2f;
  sphere.color.a = 0.8f;
  free.markers.push_back(sphere);
  free.always_visible = true;
  msg.controls.push_back(free);
  if (!marker_->processMessage(msg)) {
    reportConfigError(this, "Marker", "rviz rejected the interactive marker");
  }
}

void GoalStateDisplay::showGoal(bool reachable) {
  reachable_ = reachable;
  robot_->setState(goal_);
  updateAppearance();
  if (reachable) publishGoal();
}

void GoalStateDisplay::publishGoal() {
  sensor_msgs::JointState msg = toJointState(goal_);
  msg.header.stamp = ros::Time::now();
  goal_pub_.publish(msg);
}

void GoalStateDisplay::updateAppearance() {
  if (!robot_) return;
  const QColor color = reachable_ ? reachable_color_property_->getColor() : unreachable_color_property_->getColor();
  robot_->setColor(color.redF(), color.greenF(), color.blueF());
  robot_->setAlpha(alpha_property_->getFloat());
}

void GoalStateDisplay::updateJointStateTopic() {
  joint_state_sub_.shutdown();
  if (!isEnabled()) return;
  joint_state_sub_ = update_nh_.subscribe<sensor_msgs::JointState>(
      joint_state_topic_property_->getStdString(), 1, [this](const sensor_msgs::JointStateConstPtr& msg) {
        latest_joint_state_ = *msg;
        // The goal starts at the robot's current state once that is known.
        if (model_ && marker_ && !marker_on_current_state_) startFromCurrentState(*msg);
      });
}

void GoalStateDisplay::onEnable() {
  if (robot_) {
    robot_->setVisible(true);
    if (!marker_) createMarker();
  }
  updateJointStateTopic();
  updateGoalPoseTopic();
}

void GoalStateDisplay::onDisable() {
  joint_state_sub_.shutdown();
  goal_pose_sub_.shutdown();
  if (robot_) robot_->setVisible(false);
  marker_.reset();
}

void GoalStateDisplay::reset() {
  rviz::Display::reset();
  loadModel();
}

void GoalStateDisplay::processFeedback(visualization_msgs::InteractiveMarkerFeedback& feedback) {
  if (feedback.event_type != visualization_msgs::InteractiveMarkerFeedback::POSE_UPDATE || !model_) return;
  geometry_msgs::PoseStamped pose;
  pose.header.frame_id = feedback.header.frame_id;
  pose.pose = feedback.pose;
  requestIk(pose);
}

void GoalStateDisplay::updateGoalPoseTopic() {
  goal_pose_sub_.shutdown();
  if (!isEnabled() || goal_pose_topic_property_->getStdString().empty()) return;
  goal_pose_sub_ = update_nh_.subscribe(goal_pose_topic_property_->getStdString(), 1,
                                        &GoalStateDisplay::goalPoseCallback, this);
}

void GoalStateDisplay::goalPoseCallback(const geometry_msgs::PoseStamped::ConstPtr& msg) {
  if (!model_ || !marker_) return;
  // The marker lives in the root link's frame; other frames would need a tf lookup the marker does not do.
  if (!msg->header.frame_id.empty() && msg->header.frame_id != fk_->rootLink()) {
    reportConfigError(this, "Goal Pose", "goal pose in frame '" + msg->header.frame_id + "', expected '" +
                                             fk_->rootLink() + "'");
    return;
  }
  deleteStatusStd("Goal Pose");
  geometry_msgs::PoseStamped pose = *msg;
  pose.header.frame_id = fk_->rootLink();
  placeMarkerAt(pose.pose);
  requestIk(pose);
}

void GoalStateDisplay::requestIk(const geometry_msgs::PoseStamped& pose) {
  GoalIkRequest request;
  request.pose = pose;
  request.group = group_;
  request.tip_link = tip_link_;
  request.seed = toJointState(goal_);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_request_ = request;  // only the latest pose matters
    ik_period_ = 1.0 / ik_rate_property_->getFloat();
  }
  wake_.notify_all();
}

void GoalStateDisplay::update(float wall_dt, float /*ros_dt*/) {
  if (!robot_ || !marker_) return;
  if (!robot_->updateRootPose()) {
    setStatusStd(rviz::StatusProperty::Error, "Transform",
                 "no transform from '" + fk_->rootLink() + "' to '" + fixed_frame_.toStdString() + "'");
  } else {
    deleteStatusStd("Transform");
  }
  marker_->update(wall_dt);
  std::optional<GoalIkOutcome> outcome;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    outcome.swap(outcome_);
  }
  if (!outcome) return;
  for (const auto& [name, value] : outcome->solution) goal_[name] = value;
  switch (outcome->kind) {
    case GoalIkOutcome::Kind::kValid:
      setStatusStd(rviz::StatusProperty::Ok, "Goal", outcome->message);
      showGoal(true);
      break;
    case GoalIkOutcome::Kind::kInCollision:
    case GoalIkOutcome::Kind::kNoSolution:
      setStatusStd(rviz::StatusProperty::Warn, "Goal", outcome->message);
      showGoal(false);
      break;
    case GoalIkOutcome::Kind::kError:
      setStatusStd(rviz::StatusProperty::Error, "Goal", outcome->message);
      showGoal(false);
      break;
  }
}

}  // namespace sixdof_rviz

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(sixdof_rviz::GoalStateDisplay, rviz::Display)
