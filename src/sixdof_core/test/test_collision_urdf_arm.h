#pragma once
// Test and benchmark helper: builds LinkGeometry and link poses straight from the URDF with urdfdom, so the collision
// tests need no robot-model class.
#include <functional>
#include <stdexcept>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>

#include "sixdof_core/geometry.h"

namespace sixdof_test {

inline Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d tf = Eigen::Isometry3d::Identity();
  tf.translation() << pose.position.x, pose.position.y, pose.position.z;
  tf.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).matrix();
  return tf;
}

struct UrdfArm {
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> order;  // link order = depth-first from the root
  std::vector<sixdof_core::LinkGeometry> links;
  std::vector<std::pair<std::string, std::string>> adjacent;

  // description_dir resolves package://sixdof_description/ mesh URIs.
  UrdfArm(const std::string& path, const std::string& description_dir) : model(urdf::parseURDFFile(path)) {
    if (!model) throw std::runtime_error("cannot parse " + path);
    std::function<void(const urdf::LinkConstSharedPtr&)> visit = [&](const urdf::LinkConstSharedPtr& link) {
      order.push_back(link->name);
      sixdof_core::LinkGeometry geometry;
      geometry.link_name = link->name;
      for (const auto& collision : link->collision_array) {
        sixdof_core::PlacedShape placed;
        placed.origin = toIsometry(collision->origin);
        const auto& g = collision->geometry;
        if (g->type == urdf::Geometry::BOX) {
          auto box = std::static_pointer_cast<urdf::Box>(g);
          placed.shape.type = sixdof_core::Shape::Type::kBox;
          placed.shape.box_size << box->dim.x, box->dim.y, box->dim.z;
        } else if (g->type == urdf::Geometry::SPHERE) {
          placed.shape.type = sixdof_core::Shape::Type::kSphere;
          placed.shape.radius = std::static_pointer_cast<urdf::Sphere>(g)->radius;
        } else if (g->type == urdf::Geometry::CYLINDER) {
          auto cyl = std::static_pointer_cast<urdf::Cylinder>(g);
          placed.shape.type = sixdof_core::Shape::Type::kCylinder;
          placed.shape.radius = cyl->radius;
          placed.shape.length = cyl->length;
        } else {
          auto mesh = std::static_pointer_cast<urdf::Mesh>(g);
          placed.shape.type = sixdof_core::Shape::Type::kMesh;
          std::string file = mesh->filename;
          const std::string prefix = "package://sixdof_description/";
          if (file.rfind(prefix, 0) == 0) file = description_dir + "/" + file.substr(prefix.size());
          placed.shape.mesh_path = file;
          placed.shape.mesh_scale << mesh->scale.x, mesh->scale.y, mesh->scale.z;
        }
        geometry.shapes.push_back(placed);
      }
      links.push_back(geometry);
      for (const auto& child : link->child_links) {
        adjacent.emplace_back(link->name, child->name);
        visit(child);
      }
    };
    visit(model->getRoot());
  }

  // `count` sets of link poses at joint values drawn uniformly within the limits (mimic joints follow), from `seed`.
  std::vector<std::vector<Eigen::Isometry3d>> randomPoses(int count, unsigned seed) const {
    std::mt19937 rng(seed);
    std::vector<std::vector<Eigen::Isometry3d>> states;
    for (int k = 0; k < count; ++k) {
      std::map<std::string, double> values;
      for (const auto& [name, joint] : model->joints_) {
        if (joint->limits && !joint->mimic) {
          values[name] = std::uniform_real_distribution<double>(joint->limits->lower, joint->limits->upper)(rng);
        }
      }
      states.push_back(poses(values));
    }
    return states;
  }

  // World poses of all links (in `order`) for the given joint values (missing joints = 0, mimics follow).
  std::vector<Eigen::Isometry3d> poses(const std::map<std::string, double>& values) const {
    std::map<std::string, Eigen::Isometry3d> by_name;
    by_name[order.front()] = Eigen::Isometry3d::Identity();
    auto value = [&](const urdf::Joint& joint) {
      if (joint.mimic) {
        auto it = values.find(joint.mimic->joint_name);
        return (it == values.end() ? 0.0 : it->second) * joint.mimic->multiplier + joint.mimic->offset;
      }
      auto it = values.find(joint.name);
      return it == values.end() ? 0.0 : it->second;
    };
    std::vector<Eigen::Isometry3d> out;
    for (const std::string& name : order) {
      auto link = model->getLink(name);
      if (link->parent_joint) {
        const urdf::Joint& joint = *link->parent_joint;
        Eigen::Isometry3d tf = by_name.at(joint.parent_link_name) * toIsometry(joint.parent_to_joint_origin_transform);
        const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
        if (joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS) {
          tf.rotate(Eigen::AngleAxisd(value(joint), axis));
        } else if (joint.type == urdf::Joint::PRISMATIC) {
          tf.translate(axis * value(joint));
        }
        by_name[name] = tf;
      }
      out.push_back(by_name.at(name));
    }
    return out;
  }
};

}  // namespace sixdof_test
