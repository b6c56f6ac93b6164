#pragma once

#include <memory>
#include <string>

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include "sixdof_rviz/link_poses.h"

namespace Ogre {
class SceneNode;
}
namespace rviz {
class Display;
class DisplayContext;
class Property;
class Robot;
}  // namespace rviz

namespace sixdof_rviz {

// Sets an Error status on `display` and logs it once: configuration errors must show in rviz's log too.
void reportConfigError(rviz::Display* display, const std::string& status_name, const std::string& text);

// A robot drawn with rviz's own robot rendering (the URDF's visual meshes) at a given joint state, in one colour.
class GhostRobot {
 public:
  GhostRobot(Ogre::SceneNode* parent_node, rviz::DisplayContext* context, const std::string& name,
             rviz::Property* parent_property, const urdf::ModelInterface& urdf, std::shared_ptr<const LinkPoses> fk);
  ~GhostRobot();

  void setState(const JointValues& values);
  void setColor(float red, float green, float blue);  // 0..1
  void setAlpha(float alpha);
  void setVisible(bool visible);
  // Places the root link in the fixed frame; false when tf cannot say where it is.
  bool updateRootPose();

 private:
  rviz::DisplayContext* context_;
  // Holds rviz::Robot's link properties: rviz::Robot never deletes its own "Links" property.
  std::unique_ptr<rviz::Property> properties_;
  std::unique_ptr<rviz::Robot> robot_;
  std::shared_ptr<const LinkPoses> fk_;
};

}  // namespace sixdof_rviz
