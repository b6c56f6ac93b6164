#include "sixdof_sim/urdf_loader.h"

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>

#include "sixdof_sim/grasp_fix.h"

namespace sixdof_sim {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  t.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

Shape toShape(const urdf::Geometry& geometry, const std::string& link_name) {
  Shape shape;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(geometry);
      shape.type = ShapeType::kBox;
      shape.box_size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      shape.type = ShapeType::kCylinder;
      shape.radius = cylinder.radius;
      shape.length = cylinder.length;
      break;
    }
    case urdf::Geometry::SPHERE: {
      shape.type = ShapeType::kSphere;
      shape.radius = static_cast<const urdf::Sphere&>(geometry).radius;
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
      shape.type = ShapeType::kMesh;
      shape.mesh_resource = mesh.filename;
      shape.mesh_scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      break;
    }
    default:
      throw std::invalid_argument("URDF link '" + link_name + "': unsupported collision geometry type");
  }
  return shape;
}

// <gazebo reference="link"><mu1>value</mu1></gazebo> for every link that has one.
std::map<std::string, double> parseLinkFriction(const std::string& urdf_xml) {
  std::map<std::string, double> friction;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::invalid_argument(std::string("URDF is not valid XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) return friction;
  for (const tinyxml2::XMLElement* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    const char* reference = gazebo->Attribute("reference");
    const tinyxml2::XMLElement* mu1 = gazebo->FirstChildElement("mu1");
    if (reference == nullptr || mu1 == nullptr) continue;
    double value = 0.0;
    if (mu1->QueryDoubleText(&value) != tinyxml2::XML_SUCCESS || !std::isfinite(value) || value < 0.0) {
      throw std::invalid_argument(std::string("URDF <gazebo reference=\"") + reference +
                                  "\">: <mu1> must be a non-negative number");
    }
    friction[reference] = value;
  }
  return friction;
}

}  // namespace

RobotDescription parseRobotDescription(const std::string& urdf_xml) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw std::invalid_argument("URDF could not be parsed (see urdfdom's message above)");
  const urdf::LinkConstSharedPtr root = model->getRoot();
  if (!root) throw std::invalid_argument("URDF has no root link");

  RobotDescription description;
  description.name = model->getName();
  description.root_link = root->name;
  description.grasp_fix = parseGraspFixConfig(urdf_xml);
  const std::map<std::string, double> friction = parseLinkFriction(urdf_xml);
  for (const auto& entry : friction) {
    if (!model->getLink(entry.first)) {
      throw std::invalid_argument("URDF <gazebo reference=\"" + entry.first + "\">: no such link");
    }
  }

  // Depth-first, children in URDF order: parents always precede children.
  std::function<void(const urdf::LinkConstSharedPtr&)> visit = [&](const urdf::LinkConstSharedPtr& link) {
    RobotLink out;
    out.name = link->name;
    if (link->inertial) {
      const urdf::Inertial& inertial = *link->inertial;
      const Eigen::Isometry3d frame = toIsometry(inertial.origin);
      Eigen::Matrix3d inertia;
      inertia << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy, inertial.iyz, inertial.ixz,
          inertial.iyz, inertial.izz;
      if (!std::isfinite(inertial.mass) || inertial.mass < 0.0) {
        throw std::invalid_argument("URDF link '" + link->name + "': mass must be >= 0");
      }
      out.mass = inertial.mass;
      out.com = frame.translation();
      out.inertia = frame.linear() * inertia * frame.linear().transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(out.inertia);
      if (!inertia.allFinite() || eig.eigenvalues().minCoeff() < 0.0) {
        throw std::invalid_argument("URDF link '" + link->name + "': inertia is not positive semi-definite");
      }
    }
    for (const urdf::CollisionSharedPtr& collision : link->collision_array) {
      if (!collision || !collision->geometry) continue;
      out.collisions.push_back({toShape(*collision->geometry, link->name), toIsometry(collision->origin)});
    }
    const auto f = friction.find(link->name);
    if (f != friction.end()) out.friction = f->second;
    description.links.push_back(out);

    if (link->parent_joint) {
      const urdf::Joint& joint = *link->parent_joint;
      RobotJoint rj;
      rj.info.name = joint.name;
      rj.info.parent_link = joint.parent_link_name;
      rj.info.child_link = joint.child_link_name;
      rj.origin = toIsometry(joint.parent_to_joint_origin_transform);
      switch (joint.type) {
        case urdf::Joint::FIXED:
          rj.fixed = true;
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
          rj.info.type = JointType::kRevolute;
          break;
        case urdf::Joint::PRISMATIC:
          rj.info.type = JointType::kPrismatic;
          break;
        default:
          throw std::invalid_argument("URDF joint '" + joint.name +
                                      "': only revolute, continuous, prismatic and fixed joints are supported");
      }
      if (!rj.fixed) {
        Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
        if (!(axis.norm() > 1e-9)) throw std::invalid_argument("URDF joint '" + joint.name + "': zero axis");
        rj.axis = axis.normalized();
        if (joint.type == urdf::Joint::CONTINUOUS) {
          rj.info.lower = -std::numeric_limits<double>::infinity();
          rj.info.upper = std::numeric_limits<double>::infinity();
        } else {
          if (!joint.limits) throw std::invalid_argument("URDF joint '" + joint.name + "': <limit> missing");
          rj.info.lower = joint.limits->lower;
          rj.info.upper = joint.limits->upper;
          if (!(rj.info.lower <= rj.info.upper)) {
            throw std::invalid_argument("URDF joint '" + joint.name + "': lower limit above upper limit");
          }
        }
        if (joint.limits) {
          rj.info.max_velocity = joint.limits->velocity;
          rj.info.max_effort = joint.limits->effort;
        }
        if (!(rj.info.max_effort > 0.0)) {
          throw std::invalid_argument("URDF joint '" + joint.name + "': <limit effort> must be > 0 (servo bound)");
        }
        if (joint.dynamics) {
          rj.info.damping = joint.dynamics->damping;
          rj.info.friction = joint.dynamics->friction;
          if (rj.info.damping < 0.0 || rj.info.friction < 0.0) {
            throw std::invalid_argument("URDF joint '" + joint.name + "': negative damping or friction");
          }
        }
        if (joint.mimic) {
          rj.info.mimic_of = joint.mimic->joint_name;
          rj.info.mimic_multiplier = joint.mimic->multiplier;
          rj.info.mimic_offset = joint.mimic->offset;
        }
        if (out.mass <= 0.0) {
          throw std::invalid_argument("URDF link '" + link->name + "': a link moved by joint '" + joint.name +
                                      "' needs an <inertial> with mass > 0");
        }
      }
      description.joints.push_back(rj);
    }
    for (const urdf::LinkSharedPtr& child : link->child_links) visit(child);
  };
  visit(root);

  for (const RobotJoint& joint : description.joints) {
    if (joint.info.mimic_of.empty()) continue;
    bool found = false;
    for (const RobotJoint& other : description.joints) {
      if (other.info.name == joint.info.mimic_of && !other.fixed && other.info.mimic_of.empty()) found = true;
    }
    if (!found) {
      throw std::invalid_argument("URDF joint '" + joint.info.name + "' mimics '" + joint.info.mimic_of +
                                  "', which is not a non-mimic moving joint");
    }
  }
  return description;
}

}  // namespace sixdof_sim
