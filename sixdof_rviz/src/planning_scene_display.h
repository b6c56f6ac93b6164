#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <moveit_msgs/PlanningScene.h>
#include <rviz/display.h>

namespace Ogre {
class SceneNode;
}
namespace rviz {
class ColorProperty;
class FloatProperty;
class RosTopicProperty;
class Shape;
}  // namespace rviz

namespace sixdof_rviz {

// "sixdof_rviz/PlanningScene": draws the world's collision objects and the objects attached to robot links (e.g. a
// grasped cube in the gripper) of the full scene move_group publishes, latched, after each change
// (move_group/monitored_planning_scene), following tf: their primitives (boxes, spheres, cylinders) and their
// triangle meshes, in the scene's object colours where it gives them.
class PlanningSceneDisplay : public rviz::Display {
  Q_OBJECT
 public:
  PlanningSceneDisplay();
  ~PlanningSceneDisplay() override;

 protected:
  void onEnable() override;
  void onDisable() override;
  void update(float wall_dt, float ros_dt) override;
  void reset() override;

 private Q_SLOTS:
  void updateTopic();
  void updateSettings();

 private:
  struct DrawnObject {
    std::string frame;
    Ogre::SceneNode* node;
    std::vector<std::unique_ptr<rviz::Shape>> shapes;
  };

  void subscribe();
  void incomingScene(const moveit_msgs::PlanningScene::ConstPtr& scene);
  void rebuild(const moveit_msgs::PlanningScene& scene);
  void addObject(const moveit_msgs::CollisionObject& object, const std::string& frame, bool attached,
                 const std::optional<std_msgs::ColorRGBA>& color);
  void clearObjects();

  rviz::RosTopicProperty* topic_property_;
  rviz::ColorProperty* world_color_property_;
  rviz::ColorProperty* attached_color_property_;
  rviz::FloatProperty* alpha_property_;

  std::vector<DrawnObject> objects_;
  std::vector<std::string> object_statuses_;  // "Object <id>" warnings of the scene drawn now
  std::optional<moveit_msgs::PlanningScene> shown_scene_;
  ros::Subscriber sub_;
};

}  // namespace sixdof_rviz
