#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <Eigen/Geometry>
#include <geometry_msgs/PoseStamped.h>
#include <rviz/display.h>
#include <sensor_msgs/JointState.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "sixdof_rviz/goal_ik.h"
#include "sixdof_rviz/link_poses.h"
#include "sixdof_rviz/semantic_model.h"

namespace rviz {
class ColorProperty;
class FloatProperty;
class InteractiveMarker;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace sixdof_rviz {

class GhostRobot;

// "sixdof_rviz/GoalState": a 6-DoF interactive marker on the tip link of a planning group. Dragging it (or
// publishing a pose on the goal pose topic, e.g. from a script) asks
// move_group's compute_ik (throttled, in a worker thread) and check_state_validity (GoalIk); the goal robot is drawn
// in the "reachable" colour, or in the "unreachable" colour when there is no IK solution or the solution is
// in collision. Reachable goals are published (latched) on kGoalStateTopic for the MotionPlanningPanel.
class GoalStateDisplay : public rviz::Display {
  Q_OBJECT
 public:
  GoalStateDisplay();
  ~GoalStateDisplay() override;

 protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void update(float wall_dt, float ros_dt) override;
  void reset() override;

 private Q_SLOTS:
  void loadModel();
  void updateAppearance();
  void updateJointStateTopic();
  void updateGoalPoseTopic();
  void processFeedback(visualization_msgs::InteractiveMarkerFeedback& feedback);

 private:
  void createMarker();
  void startFromCurrentState(const sensor_msgs::JointState& state);
  void goalPoseCallback(const geometry_msgs::PoseStamped::ConstPtr& msg);
  void requestIk(const geometry_msgs::PoseStamped& pose);
  void placeMarker();
  void placeMarkerAt(const geometry_msgs::Pose& pose);
  void showGoal(bool reachable);
  void publishGoal();
  void ikLoop();
  void stopWorker();

  rviz::StringProperty* robot_description_property_;
  rviz::StringProperty* semantic_description_property_;
  rviz::StringProperty* group_property_;
  rviz::RosTopicProperty* joint_state_topic_property_;
  rviz::RosTopicProperty* goal_pose_topic_property_;
  rviz::FloatProperty* ik_rate_property_;
  rviz::FloatProperty* marker_scale_property_;
  rviz::FloatProperty* alpha_property_;
  rviz::ColorProperty* reachable_color_property_;
  rviz::ColorProperty* unreachable_color_property_;

  std::shared_ptr<const SemanticModel> model_;
  std::shared_ptr<const LinkPoses> fk_;
  std::string group_;
  std::string tip_link_;
  // Visual geometry of the tip link and the links below it, in the tip link's frame (all joints at 0).
  Eigen::AlignedBox3d end_effector_bounds_;
  std::unique_ptr<GhostRobot> robot_;
  std::unique_ptr<rviz::InteractiveMarker> marker_;
  ros::Subscriber joint_state_sub_;
  ros::Subscriber goal_pose_sub_;
  ros::Publisher goal_pub_;
  JointValues goal_;
  bool reachable_ = true;
  bool marker_on_current_state_ = false;
  std::optional<sensor_msgs::JointState> latest_joint_state_;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  double ik_period_ = 0.1;
  std::unique_ptr<GoalIk> ik_;  // used by the worker only
  std::optional<GoalIkRequest> pending_request_;
  std::optional<GoalIkOutcome> outcome_;
  std::thread worker_;
};

}  // namespace sixdof_rviz
