// RobotModel::parseUrdf: urdfdom's model to links, joints, shapes and inertials.
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <console_bridge/console.h>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

namespace {

// urdfdom reports the reason for a failed parse only through console_bridge; this collects it so
// the exception can name the problem.
class CollectingOutputHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      messages_ += (messages_.empty() ? "" : "; ") + text;
    }
  }
  const std::string& messages() const { return messages_; }

 private:
  std::string messages_;
};

std::mutex& urdfParseMutex() {
  static std::mutex mutex;
  return mutex;
}

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  t.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

// A URDF geometry as a Shape; a mesh keeps its URI in mesh_resource (mesh_path is resolved by the caller).
Shape toShape(const urdf::Geometry& geometry) {
  Shape shape;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(geometry);
      shape.type = Shape::Type::kBox;
      shape.box_size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::SPHERE:
      shape.type = Shape::Type::kSphere;
      shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
      break;
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      shape.type = Shape::Type::kCylinder;
      shape.radius = cylinder.radius;
      shape.length = cylinder.length;
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      shape.type = Shape::Type::kMesh;
      shape.mesh_resource = mesh.filename;
      shape.mesh_scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      break;
    }
  }
  return shape;
}

// The order in which <joint> elements appear in the URDF: urdfdom keeps joints in a map, and the
// document order is the natural variable order (joint1..joint6 before the gripper).
std::map<std::string, int> urdfJointDocumentOrder(const std::string& urdf_xml) {
  std::map<std::string, int> order;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return order;
  int n = 0;
  for (auto* e = doc.RootElement()->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
    if (const char* name = e->Attribute("name")) order.emplace(name, n++);
  }
  return order;
}

}  // namespace

void RobotModel::parseUrdf(const std::string& urdf_xml, const PackageResolver& resolver) {
  urdf::ModelInterfaceSharedPtr urdf;
  {
    std::lock_guard<std::mutex> lock(urdfParseMutex());
    CollectingOutputHandler handler;
    console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
    console_bridge::useOutputHandler(&handler);
    urdf = urdf::parseURDF(urdf_xml);
    console_bridge::useOutputHandler(previous);
    if (!urdf) {
      throw RobotModelError("URDF: " + (handler.messages().empty() ? std::string("parse failed") : handler.messages()));
    }
  }
  name_ = urdf->getName();
  const auto root = urdf->getRoot();
  if (!root) throw RobotModelError("URDF: no root link");
  const auto document_order = urdfJointDocumentOrder(urdf_xml);
  auto order_of = [&](const std::string& joint) {
    auto it = document_order.find(joint);
    return it == document_order.end() ? static_cast<int>(document_order.size()) : it->second;
  };

  // Breadth-first from the root: parents come before children, siblings in document order.
  std::vector<urdf::LinkConstSharedPtr> queue{root};
  for (size_t i = 0; i < queue.size(); ++i) {
    const auto& ulink = queue[i];
    LinkModel link;
    link.name = ulink->name;
    link.collision.link_name = ulink->name;
    for (const auto& collision : ulink->collision_array) {
      if (!collision || !collision->geometry) continue;
      PlacedShape placed{toShape(*collision->geometry), toIsometry(collision->origin)};
      if (placed.shape.type == Shape::Type::kMesh) {
        try {
          placed.shape.mesh_path = resolver.resolve(placed.shape.mesh_resource);
        } catch (const RobotModelError& e) {
          throw RobotModelError("URDF: collision mesh of link '" + ulink->name + "': " + e.what());
        }
      }
      link.collision.shapes.push_back(placed);
    }
    for (const auto& visual : ulink->visual_array) {
      if (!visual || !visual->geometry) continue;
      LinkVisual out{PlacedShape{toShape(*visual->geometry), toIsometry(visual->origin)}, std::nullopt};
      if (out.placed.shape.type == Shape::Type::kMesh) {
        // Planning needs no visuals: an unresolvable visual mesh leaves mesh_path empty for its user to report.
        try {
          out.placed.shape.mesh_path = resolver.resolve(out.placed.shape.mesh_resource);
        } catch (const RobotModelError&) {
        }
      }
      if (visual->material) {
        const auto& c = visual->material->color;
        out.rgba = Eigen::Vector4d(c.r, c.g, c.b, c.a);
      }
      link.visuals.push_back(out);
    }
    if (ulink->inertial) {
      const urdf::Inertial& in = *ulink->inertial;
      LinkInertial inertial;
      inertial.mass = in.mass;
      inertial.origin = toIsometry(in.origin);
      inertial.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      link.inertial = inertial;
    }
    const int link_index = static_cast<int>(links_.size());
    if (ulink->parent_joint) {
      const auto& ujoint = *ulink->parent_joint;
      JointModel joint;
      joint.name = ujoint.name;
      joint.parent_link = ujoint.parent_link_name;
      joint.child_link = ujoint.child_link_name;
      joint.origin = toIsometry(ujoint.parent_to_joint_origin_transform);
      joint.axis = Eigen::Vector3d(ujoint.axis.x, ujoint.axis.y, ujoint.axis.z);
      static const std::map<int, JointType> kJointTypes = {{urdf::Joint::FIXED, JointType::kFixed},
                                                           {urdf::Joint::REVOLUTE, JointType::kRevolute},
                                                           {urdf::Joint::CONTINUOUS, JointType::kContinuous},
                                                           {urdf::Joint::PRISMATIC, JointType::kPrismatic}};
      const auto type = kJointTypes.find(ujoint.type);
      if (type == kJointTypes.end()) {
        throw RobotModelError("URDF: joint '" + ujoint.name + "' has an unsupported type (only fixed, revolute, " +
                              "continuous and prismatic joints are supported)");
      }
      joint.type = type->second;
      if (joint.type != JointType::kFixed) {
        if (joint.axis.norm() < 1e-9) throw RobotModelError("URDF: joint '" + ujoint.name + "' has a zero axis");
        joint.axis.normalize();
        if (ujoint.limits) {
          joint.limits.lower = ujoint.limits->lower;
          joint.limits.upper = ujoint.limits->upper;
          joint.limits.velocity = ujoint.limits->velocity;
          joint.limits.effort = ujoint.limits->effort;
        }
        if (joint.type == JointType::kContinuous) {
          joint.limits.bounded = false;
          joint.limits.lower = -M_PI;
          joint.limits.upper = M_PI;
        } else if (!(joint.limits.lower <= joint.limits.upper) || !std::isfinite(joint.limits.lower) ||
                   !std::isfinite(joint.limits.upper)) {
          throw RobotModelError("URDF: joint '" + ujoint.name + "' has invalid limits [" +
                                std::to_string(joint.limits.lower) + ", " + std::to_string(joint.limits.upper) + "]");
        }
        if (ujoint.dynamics) {
          joint.damping = ujoint.dynamics->damping;
          joint.friction = ujoint.dynamics->friction;
        }
        if (ujoint.mimic) {
          joint.mimic = MimicInfo{ujoint.mimic->joint_name, ujoint.mimic->multiplier, ujoint.mimic->offset};
        }
      }
      const int joint_index = static_cast<int>(joints_.size());
      joint_index_[joint.name] = joint_index;
      joints_.push_back(joint);
      link.parent_joint = joint_index;
      link.parent_link = link_index_.at(ujoint.parent_link_name);
      links_[link.parent_link].child_joints.push_back(joint_index);
    }
    link_index_[link.name] = link_index;
    links_.push_back(std::move(link));

    std::vector<urdf::LinkConstSharedPtr> children(ulink->child_links.begin(), ulink->child_links.end());
    std::stable_sort(children.begin(), children.end(), [&](const auto& a, const auto& b) {
      return order_of(a->parent_joint->name) < order_of(b->parent_joint->name);
    });
    queue.insert(queue.end(), children.begin(), children.end());
  }

  // Variables: active joints in link (topological) order.
  for (size_t j = 0; j < joints_.size(); ++j) {
    auto& joint = joints_[j];
    if (joint.type == JointType::kFixed || joint.mimic) continue;
    joint.variable_index = static_cast<int>(variable_names_.size());
    variable_names_.push_back(joint.name);
    variable_joints_.push_back(static_cast<int>(j));
  }
  for (auto& joint : joints_) {
    if (!joint.mimic) continue;
    const int source = jointIndex(joint.mimic->joint);
    joint.mimic->joint_index = source;
    if (source < 0) {
      throw RobotModelError("URDF: joint '" + joint.name + "' mimics unknown joint '" + joint.mimic->joint + "'");
    }
    if (!joints_[source].isActive()) {
      throw RobotModelError("URDF: joint '" + joint.name + "' mimics '" + joint.mimic->joint +
                            "', which is not an active (non-fixed, non-mimic) joint");
    }
  }
}

}  // namespace sixdof_core
