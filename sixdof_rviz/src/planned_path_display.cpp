#include "planned_path_display.h"

#include <OgreSceneNode.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/editable_enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>
#include <urdf_parser/urdf_parser.h>

#include "ghost_robot.h"
#include "sixdof_rviz/link_poses.h"

namespace sixdof_rviz {
namespace {
constexpr char kRealtime[] = "REALTIME";
}

PlannedPathDisplay::PlannedPathDisplay() {
  robot_description_property_ =
      new rviz::StringProperty("Robot Description", "robot_description",
                               "Parameter holding the URDF of the robot to draw.", this, SLOT(loadRobot()));
  topic_property_ = new rviz::RosTopicProperty(
      "Trajectory Topic", "move_group/display_planned_path",
      QString::fromStdString(ros::message_traits::datatype<moveit_msgs::DisplayTrajectory>()),
      "moveit_msgs/DisplayTrajectory topic of planned paths.", this, SLOT(updateTopic()));
  state_time_property_ = new rviz::EditableEnumProperty(
      "State Display Time", kRealtime,
      "Seconds each state is shown, or REALTIME to follow the trajectory's time_from_start.", this);
  state_time_property_->addOptionStd(kRealtime);
  for (const char* option : {"0.05 s", "0.1 s", "0.5 s"}) state_time_property_->addOptionStd(option);
  loop_property_ = new rviz::BoolProperty("Loop Animation", false, "Restart the animation at the end.", this);
  interrupt_property_ = new rviz::BoolProperty(
      "Interrupt Display", false, "Show a new trajectory at once instead of after the current animation.", this);
  trail_property_ = new rviz::BoolProperty("Show Trail", false, "Show every Nth state of the path at once.", this,
                                           SLOT(updateTrail()));
  trail_step_property_ =
      new rviz::IntProperty("Trail Step Size", 1, "N: every Nth state is in the trail.", this, SLOT(updateTrail()));
  trail_step_property_->setMin(1);
  alpha_property_ = new rviz::FloatProperty("Robot Alpha", 0.5f, "Opacity of the ghost robot.", this,
                                            SLOT(updateAppearance()));
  alpha_property_->setMin(0.0f);
  alpha_property_->setMax(1.0f);
  color_property_ = new rviz::ColorProperty("Robot Color", QColor(150, 50, 150), "Colour of the ghost robot.", this,
                                            SLOT(updateAppearance()));
}

PlannedPathDisplay::~PlannedPathDisplay() = default;

void PlannedPathDisplay::onInitialize() { loadRobot(); }

void PlannedPathDisplay::loadRobot() {
  if (context_ == nullptr) return;
  trail_.clear();
  robot_.reset();
  animation_.clear();
  shown_index_.reset();
  std::string urdf_xml;
  const std::string param = robot_description_property_->getStdString();
  if (!update_nh_.getParam(param, urdf_xml)) {
    reportConfigError(this, "Robot", "parameter '" + param + "' is not set");
    return;
  }
  urdf_ = urdf::parseURDF(urdf_xml);
  if (!urdf_ || !urdf_->getRoot()) {
    reportConfigError(this, "Robot", "parameter '" + param + "' holds no valid URDF");
    return;
  }
  try {
    fk_ = std::make_shared<LinkPoses>(loadRobotModel(urdf_xml));
  } catch (const std::invalid_argument& e) {
    reportConfigError(this, "Robot", e.what());
    return;
  }
  robot_ = std::make_unique<GhostRobot>(scene_node_, context_, "Planned Path", this, *urdf_, fk_);
  applyAppearance(robot_.get());
  robot_->setVisible(false);
  setStatusStd(rviz::StatusProperty::Ok, "Robot", "loaded from '" + param + "'");
}

void PlannedPathDisplay::onEnable() {
  subscribe();
  // Enabling the display made its whole scene node visible: hide the ghost until it has a state to show.
  if (robot_) robot_->setVisible(shown_index_.has_value());
  for (auto& ghost : trail_) ghost->setVisible(true);
}

void PlannedPathDisplay::onDisable() {
  unsubscribe();
  if (robot_) robot_->setVisible(false);
  for (auto& ghost : trail_) ghost->setVisible(false);
}

void PlannedPathDisplay::reset() {
  rviz::Display::reset();
  loadRobot();
  updateTopic();
}

void PlannedPathDisplay::updateTopic() {
  unsubscribe();
  if (isEnabled()) subscribe();
}

void PlannedPathDisplay::subscribe() {
  const std::string topic = topic_property_->getStdString();
  if (topic.empty()) {
    reportConfigError(this, "Topic", "no topic set");
    return;
  }
  try {
    sub_ = update_nh_.subscribe(topic, 2, &PlannedPathDisplay::incomingTrajectory, this);
    setStatusStd(rviz::StatusProperty::Ok, "Topic", "subscribed to " + topic);
  } catch (const ros::Exception& e) {
    reportConfigError(this, "Topic", std::string("cannot subscribe: ") + e.what());
  }
}

void PlannedPathDisplay::unsubscribe() { sub_.shutdown(); }

void PlannedPathDisplay::applyAppearance(GhostRobot* robot) const {
  const QColor color = color_property_->getColor();
  robot->setColor(color.redF(), color.greenF(), color.blueF());
  robot->setAlpha(alpha_property_->getFloat());
}

void PlannedPathDisplay::updateAppearance() {
  if (robot_) applyAppearance(robot_.get());
  for (auto& ghost : trail_) applyAppearance(ghost.get());
}

void PlannedPathDisplay::updateTrail() {
  trail_.clear();
  if (!trail_property_->getBool() || !robot_ || animation_.empty()) return;
  const auto& states = animation_.states().states;
  const size_t step = static_cast<size_t>(trail_step_property_->getInt());
  for (size_t i = 0; i < states.size(); i += step) {
    trail_.push_back(std::make_unique<GhostRobot>(scene_node_, context_, "Trail", nullptr, *urdf_, fk_));
    applyAppearance(trail_.back().get());
    trail_.back()->setState(states[i]);
    trail_.back()->updateRootPose();
    trail_.back()->setVisible(isEnabled());
  }
}

void PlannedPathDisplay::incomingTrajectory(const moveit_msgs::DisplayTrajectory::ConstPtr& msg) {
  std::string error;
  auto states = toTrajectoryStates(*msg, &error);
  if (!states) {
    reportConfigError(this, "Trajectory", "rejected: " + error);
    return;
  }
  setStatusStd(rviz::StatusProperty::Ok, "Trajectory",
               std::to_string(states->states.size()) + " states, " + std::to_string(states->times.back()) + " s");
  animation_.offer(std::move(*states), interrupt_property_->getBool());
}

std::optional<double> PlannedPathDisplay::stateDisplayTime() {
  const std::string text = state_time_property_->getStdString();
  if (text == kRealtime) return std::nullopt;
  try {
    size_t used = 0;
    double seconds = std::stod(text, &used);
    const std::string rest = text.substr(used);
    if (seconds > 0.0 && (rest.empty() || rest == " s" || rest == "s")) {
      deleteStatusStd("State Display Time");
      return seconds;
    }
  } catch (const std::exception&) {
  }
  setStatusStd(rviz::StatusProperty::Error, "State Display Time",
               "'" + text + "' is neither REALTIME nor a positive number of seconds; showing in real time");
  return std::nullopt;
}

void PlannedPathDisplay::update(float wall_dt, float /*ros_dt*/) {
  if (!robot_) return;
  if (!robot_->updateRootPose()) {
    setStatusStd(rviz::StatusProperty::Error, "Transform",
                 "no transform from '" + fk_->rootLink() + "' to '" + fixed_frame_.toStdString() + "'");
    return;
  }
  deleteStatusStd("Transform");
  for (auto& ghost : trail_) ghost->updateRootPose();
  auto index = animation_.advance(wall_dt, loop_property_->getBool(), stateDisplayTime());
  if (animation_.generation() != shown_generation_) {
    shown_generation_ = animation_.generation();
    shown_index_.reset();
    updateTrail();
  }
  if (!index) return;
  if (index != shown_index_) {
    robot_->setState(animation_.states().states[*index]);
    if (!shown_index_) robot_->setVisible(true);
    shown_index_ = index;
  }
}

}  // namespace sixdof_rviz

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(sixdof_rviz::PlannedPathDisplay, rviz::Display)
