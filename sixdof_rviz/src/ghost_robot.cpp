#include "ghost_robot.h"

#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <ros/console.h>
#include <rviz/display.h>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/property.h>
#include <rviz/robot/link_updater.h>
#include <rviz/robot/robot.h>
#include <rviz/robot/robot_link.h>

namespace sixdof_rviz {
namespace {

class PoseMapUpdater : public rviz::LinkUpdater {
 public:
  explicit PoseMapUpdater(const LinkPoseMap& poses) : poses_(poses) {}

  bool getLinkTransforms(const std::string& link_name, Ogre::Vector3& visual_position,
                         Ogre::Quaternion& visual_orientation, Ogre::Vector3& collision_position,
                         Ogre::Quaternion& collision_orientation) const override {
    auto it = poses_.find(link_name);
    if (it == poses_.end()) return false;
    const Eigen::Vector3d p = it->second.translation();
    const Eigen::Quaterniond q(it->second.rotation());
    visual_position = collision_position = Ogre::Vector3(p.x(), p.y(), p.z());
    visual_orientation = collision_orientation = Ogre::Quaternion(q.w(), q.x(), q.y(), q.z());
    return true;
  }

 private:
  const LinkPoseMap& poses_;
};

}  // namespace

void reportConfigError(rviz::Display* display, const std::string& status_name, const std::string& text) {
  display->setStatusStd(rviz::StatusProperty::Error, status_name, text);
  ROS_ERROR_STREAM(display->getNameStd() << ": " << text);
}

GhostRobot::GhostRobot(Ogre::SceneNode* parent_node, rviz::DisplayContext* context, const std::string& name,
                       rviz::Property* parent_property, const urdf::ModelInterface& urdf,
                       std::shared_ptr<const LinkPoses> fk)
    : context_(context),
      properties_(std::make_unique<rviz::Property>(QString::fromStdString(name), QVariant(), "", parent_property)),
      robot_(std::make_unique<rviz::Robot>(parent_node, context, name, properties_.get())),
      fk_(std::move(fk)) {
  robot_->load(urdf, true, false);
  robot_->setVisualVisible(true);
  robot_->setCollisionVisible(false);
}

// Members go in reverse order: the robot before the property holding its link properties.
GhostRobot::~GhostRobot() = default;

void GhostRobot::setState(const JointValues& values) { robot_->update(PoseMapUpdater(fk_->compute(values))); }

void GhostRobot::setColor(float red, float green, float blue) {
  for (const auto& [name, link] : robot_->getLinks()) link->setColor(red, green, blue);
}

void GhostRobot::setAlpha(float alpha) { robot_->setAlpha(alpha); }

void GhostRobot::setVisible(bool visible) { robot_->setVisible(visible); }

bool GhostRobot::updateRootPose() {
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!context_->getFrameManager()->getTransform(fk_->rootLink(), ros::Time(), position, orientation)) return false;
  robot_->setPosition(position);
  robot_->setOrientation(orientation);
  return true;
}

}  // namespace sixdof_rviz
