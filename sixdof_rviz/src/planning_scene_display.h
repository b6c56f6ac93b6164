#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <rviz/display.h>
#include <sixdof_msgs/PlanningScene.h>

namespace Ogre {
class SceneNode;
}
namespace rviz {
class ColorProperty;
class FloatProperty;
class Shape;
class StringProperty;
}  // namespace rviz

namespace sixdof_rviz {

// "sixdof_rviz/PlanningScene": polls move_group's get_planning_scene and draws the world's collision objects
// and the objects attached to robot links (e.g. a grasped cube in the gripper), following tf: their primitives
// (boxes, spheres, cylinders) and their triangle meshes.
class PlanningSceneDisplay : public rviz::Display {
  Q_OBJECT
 public:
  PlanningSceneDisplay();
  ~PlanningSceneDisplay() override;

 protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void update(float wall_dt, float ros_dt) override;
  void reset() override;

 private Q_SLOTS:
  void updateSettings();

 private:
  struct DrawnObject {
    std::string frame;
    Ogre::SceneNode* node;
    std::vector<std::unique_ptr<rviz::Shape>> shapes;
  };

  void pollLoop();
  void rebuild(const sixdof_msgs::PlanningScene& scene);
  void addObject(const sixdof_msgs::CollisionObject& object, const std::string& frame, bool attached);
  void clearObjects();

  rviz::StringProperty* service_property_;
  rviz::FloatProperty* rate_property_;
  rviz::ColorProperty* world_color_property_;
  rviz::ColorProperty* attached_color_property_;
  rviz::FloatProperty* alpha_property_;

  std::vector<DrawnObject> objects_;
  std::vector<std::string> object_statuses_;  // "Object <id>" warnings of the scene drawn now
  std::optional<sixdof_msgs::PlanningScene> shown_scene_;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool polling_ = false;
  std::string service_;
  double period_ = 0.5;
  std::optional<sixdof_msgs::PlanningScene> received_;
  std::optional<std::string> poll_error_;
  std::thread worker_;
};

}  // namespace sixdof_rviz
