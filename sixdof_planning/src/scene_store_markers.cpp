// The scene as rviz markers: world objects in the planning frame, attached objects on their links.
#include "sixdof_planning/scene_store.h"

#include <shape_msgs/SolidPrimitive.h>

#include "sixdof_planning/conversions.h"

namespace sixdof_planning {

namespace {

visualization_msgs::Marker shapeMarker(const std::string& frame, const std::string& ns, int id,
                                       const Eigen::Isometry3d& pose, bool attached) {
  visualization_msgs::Marker marker;
  marker.header.frame_id = frame;
  marker.ns = ns;
  marker.id = id;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose = eigenToPose(pose);
  marker.color.a = 0.8;
  // MoveIt's colours: world objects green, attached objects purple.
  marker.color.r = attached ? 0.6 : 0.2;
  marker.color.g = attached ? 0.2 : 0.8;
  marker.color.b = attached ? 0.8 : 0.2;
  return marker;
}

void addObjectMarkers(const moveit_msgs::CollisionObject& object, const std::string& frame, bool attached,
                      visualization_msgs::MarkerArray* markers) {
  const Eigen::Isometry3d object_pose = poseToEigen(object.pose);
  int id = 0;
  for (size_t i = 0; i < object.primitives.size(); ++i) {
    const auto& primitive = object.primitives[i];
    auto marker = shapeMarker(frame, object.id, id++, object_pose * poseToEigen(object.primitive_poses[i]), attached);
    if (primitive.type == shape_msgs::SolidPrimitive::BOX) {
      marker.type = visualization_msgs::Marker::CUBE;
      marker.scale.x = primitive.dimensions[0];
      marker.scale.y = primitive.dimensions[1];
      marker.scale.z = primitive.dimensions[2];
    } else if (primitive.type == shape_msgs::SolidPrimitive::SPHERE) {
      marker.type = visualization_msgs::Marker::SPHERE;
      marker.scale.x = marker.scale.y = marker.scale.z = 2.0 * primitive.dimensions[0];
    } else {
      marker.type = visualization_msgs::Marker::CYLINDER;
      marker.scale.x = marker.scale.y = 2.0 * primitive.dimensions[1];
      marker.scale.z = primitive.dimensions[0];
    }
    markers->markers.push_back(marker);
  }
  for (size_t i = 0; i < object.meshes.size(); ++i) {
    auto marker = shapeMarker(frame, object.id, id++, object_pose * poseToEigen(object.mesh_poses[i]), attached);
    marker.type = visualization_msgs::Marker::TRIANGLE_LIST;
    marker.scale.x = marker.scale.y = marker.scale.z = 1.0;
    for (const auto& t : object.meshes[i].triangles) {
      for (auto index : t.vertex_indices) marker.points.push_back(object.meshes[i].vertices[index]);
    }
    markers->markers.push_back(marker);
  }
}

}  // namespace

visualization_msgs::MarkerArray SceneStore::markers() const {
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.header.frame_id = model_->rootLink();
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  for (const auto& entry : world_) addObjectMarkers(entry.second, model_->rootLink(), false, &markers);
  for (const auto& entry : attached_) addObjectMarkers(entry.second.object, entry.second.link_name, true, &markers);
  return markers;
}

}  // namespace sixdof_planning
