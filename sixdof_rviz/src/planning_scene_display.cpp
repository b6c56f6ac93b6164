#include "planning_scene_display.h"

#include <cmath>

#include <OgreMaterial.h>
#include <OgreQuaternion.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreVector3.h>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/ogre_helpers/mesh_shape.h>
#include <rviz/ogre_helpers/shape.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <shape_msgs/Mesh.h>
#include <shape_msgs/SolidPrimitive.h>

namespace sixdof_rviz {
namespace {

Ogre::Vector3 toOgre(const geometry_msgs::Point& p) { return Ogre::Vector3(p.x, p.y, p.z); }
Ogre::Quaternion toOgre(const geometry_msgs::Quaternion& q) { return Ogre::Quaternion(q.w, q.x, q.y, q.z); }

// Why a mesh cannot be drawn, or empty when it can.
std::string meshProblem(const shape_msgs::Mesh& mesh) {
  if (mesh.triangles.empty()) return "has no triangles";
  for (const auto& v : mesh.vertices) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return "has a non-finite vertex";
  }
  for (const auto& triangle : mesh.triangles) {
    for (const auto index : triangle.vertex_indices) {
      if (index >= mesh.vertices.size()) {
        return "has a vertex index " + std::to_string(index) + " out of range (" +
               std::to_string(mesh.vertices.size()) + " vertices)";
      }
    }
  }
  return "";
}

// A well-formed mesh (see meshProblem) as a shape. Each triangle gets its own three vertices with the face's
// normal, so that the faces are shaded flat. A triangle is seen from the side it winds counter-clockwise on (the
// outside of a closed mesh, as in STL files), like the primitives' faces: rviz::MeshShape draws both sides, which
// in a transparent colour (no depth writes) lets the far, unlit, faces cover the near ones.
std::unique_ptr<rviz::Shape> makeMeshShape(const shape_msgs::Mesh& mesh, Ogre::SceneManager* scene_manager,
                                           Ogre::SceneNode* parent) {
  auto shape = std::make_unique<rviz::MeshShape>(scene_manager, parent);
  shape->getMaterial()->setCullingMode(Ogre::CULL_CLOCKWISE);
  shape->estimateVertexCount(3 * mesh.triangles.size());
  shape->beginTriangles();
  for (const auto& triangle : mesh.triangles) {
    const Ogre::Vector3 a = toOgre(mesh.vertices[triangle.vertex_indices[0]]);
    const Ogre::Vector3 b = toOgre(mesh.vertices[triangle.vertex_indices[1]]);
    const Ogre::Vector3 c = toOgre(mesh.vertices[triangle.vertex_indices[2]]);
    Ogre::Vector3 normal = (b - a).crossProduct(c - a);
    normal.normalise();  // leaves a degenerate triangle's zero normal as it is
    shape->addVertex(a, normal);
    shape->addVertex(b, normal);
    shape->addVertex(c, normal);
  }
  shape->endTriangles();
  return shape;
}

// What the display draws of a scene: equal for scenes that differ only in the robot's joint values.
bool sameObjects(const moveit_msgs::PlanningScene& a, const moveit_msgs::PlanningScene& b) {
  return a.world.collision_objects == b.world.collision_objects &&
         a.robot_state.attached_collision_objects == b.robot_state.attached_collision_objects &&
         a.object_colors == b.object_colors;
}

}  // namespace

PlanningSceneDisplay::PlanningSceneDisplay() {
  topic_property_ = new rviz::RosTopicProperty(
      "Scene Topic", "move_group/monitored_planning_scene",
      QString::fromStdString(ros::message_traits::datatype<moveit_msgs::PlanningScene>()),
      "Full planning scenes (moveit_msgs/PlanningScene, is_diff false), e.g. move_group's latched "
      "monitored_planning_scene.",
      this, SLOT(updateTopic()));
  world_color_property_ = new rviz::ColorProperty(
      "World Object Color", QColor(60, 170, 60), "Colour of world collision objects the scene gives no colour.", this,
      SLOT(updateSettings()));
  attached_color_property_ = new rviz::ColorProperty(
      "Attached Object Color", QColor(140, 60, 220), "Colour of attached objects the scene gives no colour.", this,
      SLOT(updateSettings()));
  alpha_property_ = new rviz::FloatProperty("Alpha", 0.9f, "Opacity of the objects the scene gives no colour.", this,
                                            SLOT(updateSettings()));
  alpha_property_->setMin(0.0f);
  alpha_property_->setMax(1.0f);
}

PlanningSceneDisplay::~PlanningSceneDisplay() {
  sub_.shutdown();
  clearObjects();
}

void PlanningSceneDisplay::updateSettings() {
  // Colours and alpha are applied when drawing: redraw the scene we have.
  if (shown_scene_) rebuild(*shown_scene_);
}

void PlanningSceneDisplay::updateTopic() {
  if (!isEnabled()) return;
  clearObjects();
  shown_scene_.reset();
  subscribe();
}

void PlanningSceneDisplay::subscribe() {
  sub_.shutdown();
  const std::string topic = topic_property_->getStdString();
  sub_ = update_nh_.subscribe(topic, 1, &PlanningSceneDisplay::incomingScene, this);
  if (!shown_scene_) {
    setStatusStd(rviz::StatusProperty::Warn, "Scene", "no scene received on '" + sub_.getTopic() + "' yet");
  }
}

void PlanningSceneDisplay::onEnable() {
  subscribe();
  scene_node_->setVisible(true);
}

void PlanningSceneDisplay::onDisable() {
  sub_.shutdown();
  scene_node_->setVisible(false);
}

void PlanningSceneDisplay::reset() {
  rviz::Display::reset();
  clearObjects();
  shown_scene_.reset();
  if (isEnabled()) subscribe();
}

void PlanningSceneDisplay::incomingScene(const moveit_msgs::PlanningScene::ConstPtr& scene) {
  if (scene->is_diff) {
    setStatusStd(rviz::StatusProperty::Error, "Scene",
                 "received a scene diff (is_diff true) on '" + sub_.getTopic() +
                     "': this display draws full scenes only; the scene shown is unchanged");
    return;
  }
  // move_group publishes after each change; the robot's joint values do not change what is drawn.
  if (shown_scene_ && sameObjects(*shown_scene_, *scene)) return;
  shown_scene_ = *scene;
  rebuild(*scene);
}

void PlanningSceneDisplay::clearObjects() {
  for (auto& object : objects_) {
    object.shapes.clear();
    scene_manager_->destroySceneNode(object.node);
  }
  objects_.clear();
}

void PlanningSceneDisplay::addObject(const moveit_msgs::CollisionObject& object, const std::string& frame,
                                     bool attached, const std::optional<std_msgs::ColorRGBA>& scene_color) {
  DrawnObject drawn;
  drawn.frame = frame;
  drawn.node = scene_node_->createChildSceneNode();
  const QColor display_color = attached ? attached_color_property_->getColor() : world_color_property_->getColor();
  std_msgs::ColorRGBA color;
  color.r = display_color.redF();
  color.g = display_color.greenF();
  color.b = display_color.blueF();
  color.a = alpha_property_->getFloat();
  if (scene_color) color = *scene_color;
  const Ogre::Vector3 object_position = toOgre(object.pose.position);
  const Ogre::Quaternion object_orientation = toOgre(object.pose.orientation);
  // Shape i at object.pose * poses[i] (a missing pose is the identity), in the object's colour.
  const auto add = [&](std::unique_ptr<rviz::Shape> shape, const std::vector<geometry_msgs::Pose>& poses, size_t i,
                       const Ogre::Quaternion& axis_fix) {
    Ogre::Vector3 local_position = Ogre::Vector3::ZERO;
    Ogre::Quaternion local_orientation = Ogre::Quaternion::IDENTITY;
    if (i < poses.size()) {
      local_position = toOgre(poses[i].position);
      local_orientation = toOgre(poses[i].orientation);
    }
    shape->setPosition(object_position + object_orientation * local_position);
    shape->setOrientation(object_orientation * local_orientation * axis_fix);
    shape->setColor(color.r, color.g, color.b, color.a);
    drawn.shapes.push_back(std::move(shape));
  };
  std::vector<std::string> problems;
  for (size_t i = 0; i < object.primitives.size(); ++i) {
    const auto& primitive = object.primitives[i];
    const auto& d = primitive.dimensions;
    using P = shape_msgs::SolidPrimitive;
    rviz::Shape::Type type;
    Ogre::Vector3 scale;
    Ogre::Quaternion axis_fix = Ogre::Quaternion::IDENTITY;
    if (primitive.type == P::BOX && d.size() >= 3) {
      type = rviz::Shape::Cube;
      scale = Ogre::Vector3(d[P::BOX_X], d[P::BOX_Y], d[P::BOX_Z]);
    } else if (primitive.type == P::SPHERE && d.size() >= 1) {
      type = rviz::Shape::Sphere;
      scale = Ogre::Vector3(2.0 * d[P::SPHERE_RADIUS]);
    } else if (primitive.type == P::CYLINDER && d.size() >= 2) {
      type = rviz::Shape::Cylinder;
      // Ogre's cylinder is along y, SolidPrimitive's along z.
      scale = Ogre::Vector3(2.0 * d[P::CYLINDER_RADIUS], d[P::CYLINDER_HEIGHT], 2.0 * d[P::CYLINDER_RADIUS]);
      axis_fix = Ogre::Quaternion(Ogre::Degree(90), Ogre::Vector3::UNIT_X);
    } else {
      problems.push_back("primitive " + std::to_string(i) + " has an unsupported type or too few dimensions");
      continue;
    }
    auto shape = std::make_unique<rviz::Shape>(type, scene_manager_, drawn.node);
    shape->setScale(scale);
    add(std::move(shape), object.primitive_poses, i, axis_fix);
  }
  for (size_t i = 0; i < object.meshes.size(); ++i) {
    const std::string problem = meshProblem(object.meshes[i]);
    if (!problem.empty()) {
      problems.push_back("mesh " + std::to_string(i) + " " + problem + " and is not drawn");
      continue;
    }
    add(makeMeshShape(object.meshes[i], scene_manager_, drawn.node), object.mesh_poses, i, Ogre::Quaternion::IDENTITY);
  }
  for (size_t i = 0; i < object.planes.size(); ++i) {
    problems.push_back("plane " + std::to_string(i) + " is not drawn (planes are not supported)");
  }
  if (!problems.empty()) {
    std::string text = problems.front();
    for (size_t i = 1; i < problems.size(); ++i) text += "; " + problems[i];
    object_statuses_.push_back("Object " + object.id);
    setStatusStd(rviz::StatusProperty::Warn, object_statuses_.back(), text);
  }
  objects_.push_back(std::move(drawn));
}

void PlanningSceneDisplay::rebuild(const moveit_msgs::PlanningScene& scene) {
  clearObjects();
  // The objects' warnings are those of the scene drawn now.
  for (const auto& name : object_statuses_) deleteStatusStd(name);
  object_statuses_.clear();
  const auto color_of = [&scene](const std::string& id) -> std::optional<std_msgs::ColorRGBA> {
    for (const auto& object_color : scene.object_colors) {
      if (object_color.id == id) return object_color.color;
    }
    return std::nullopt;
  };
  for (const auto& object : scene.world.collision_objects) {
    addObject(object, object.header.frame_id.empty() ? fixed_frame_.toStdString() : object.header.frame_id, false,
              color_of(object.id));
  }
  for (const auto& attached : scene.robot_state.attached_collision_objects) {
    // An attached object's pose is relative to its link unless its header names another frame.
    const std::string frame =
        attached.object.header.frame_id.empty() ? attached.link_name : attached.object.header.frame_id;
    addObject(attached.object, frame, true, color_of(attached.object.id));
  }
  setStatusStd(rviz::StatusProperty::Ok, "Scene",
               std::to_string(scene.world.collision_objects.size()) + " world object(s), " +
                   std::to_string(scene.robot_state.attached_collision_objects.size()) + " attached");
}

void PlanningSceneDisplay::update(float /*wall_dt*/, float /*ros_dt*/) {
  std::string missing_frame;
  for (auto& object : objects_) {
    Ogre::Vector3 position;
    Ogre::Quaternion orientation;
    if (context_->getFrameManager()->getTransform(object.frame, ros::Time(), position, orientation)) {
      object.node->setPosition(position);
      object.node->setOrientation(orientation);
      object.node->setVisible(true);
    } else {
      object.node->setVisible(false);
      missing_frame = object.frame;
    }
  }
  if (missing_frame.empty()) {
    deleteStatusStd("Transform");
  } else {
    setStatusStd(rviz::StatusProperty::Error, "Transform", "no transform for frame '" + missing_frame + "'");
  }
}

}  // namespace sixdof_rviz

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(sixdof_rviz::PlanningSceneDisplay, rviz::Display)
