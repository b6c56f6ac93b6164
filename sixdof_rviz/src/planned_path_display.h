#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <rviz/display.h>
#include <moveit_msgs/DisplayTrajectory.h>

#include "sixdof_rviz/trajectory_animation.h"

namespace rviz {
class BoolProperty;
class ColorProperty;
class EditableEnumProperty;
class FloatProperty;
class IntProperty;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace sixdof_rviz {

class GhostRobot;
class LinkPoses;

// "sixdof_rviz/PlannedPath": animates the trajectories published on move_group/display_planned_path with a
// ghost robot, optionally with a trail of every Nth state.
class PlannedPathDisplay : public rviz::Display {
  Q_OBJECT
 public:
  PlannedPathDisplay();
  ~PlannedPathDisplay() override;

 protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void update(float wall_dt, float ros_dt) override;
  void reset() override;

 private Q_SLOTS:
  void updateTopic();
  void updateAppearance();
  void updateTrail();
  void loadRobot();

 private:
  void subscribe();
  void unsubscribe();
  void incomingTrajectory(const moveit_msgs::DisplayTrajectory::ConstPtr& msg);
  std::optional<double> stateDisplayTime();
  void applyAppearance(GhostRobot* robot) const;

  rviz::StringProperty* robot_description_property_;
  rviz::RosTopicProperty* topic_property_;
  rviz::EditableEnumProperty* state_time_property_;
  rviz::BoolProperty* loop_property_;
  rviz::BoolProperty* interrupt_property_;
  rviz::BoolProperty* trail_property_;
  rviz::IntProperty* trail_step_property_;
  rviz::FloatProperty* alpha_property_;
  rviz::ColorProperty* color_property_;

  ros::Subscriber sub_;
  urdf::ModelInterfaceSharedPtr urdf_;
  std::shared_ptr<const LinkPoses> fk_;
  std::unique_ptr<GhostRobot> robot_;
  std::vector<std::unique_ptr<GhostRobot>> trail_;
  TrajectoryAnimation animation_;
  unsigned shown_generation_ = 0;
  std::optional<size_t> shown_index_;
};

}  // namespace sixdof_rviz
