#include "sixdof_sim/urdf_loader.h"

#include <tinyxml2.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <stdexcept>

#include "gazebo_extensions.h"

namespace sixdof_sim {
namespace {

// <gazebo reference="link"><mu1>value</mu1></gazebo> for every link that has one.
std::map<std::string, double> readLinkFriction(const tinyxml2::XMLElement& robot) {
  std::map<std::string, double> friction;
  for (const tinyxml2::XMLElement* gazebo = robot.FirstChildElement("gazebo"); gazebo != nullptr;
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

RobotLink describeLink(const sixdof_core::LinkModel& link) {
  RobotLink out;
  out.name = link.name;
  if (link.inertial) {
    const sixdof_core::LinkInertial& inertial = *link.inertial;
    if (!std::isfinite(inertial.mass) || inertial.mass < 0.0) {
      throw std::invalid_argument("URDF link '" + link.name + "': mass must be >= 0");
    }
    out.mass = inertial.mass;
    out.com = inertial.origin.translation();
    out.inertia = inertial.origin.linear() * inertial.inertia * inertial.origin.linear().transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(out.inertia);
    if (!inertial.inertia.allFinite() || eig.eigenvalues().minCoeff() < 0.0) {
      throw std::invalid_argument("URDF link '" + link.name + "': inertia is not positive semi-definite");
    }
  }
  out.collisions = link.collision.shapes;
  return out;
}

RobotJoint describeJoint(const sixdof_core::JointModel& joint, const RobotLink& child) {
  using sixdof_core::JointType;
  RobotJoint rj;
  rj.info.name = joint.name;
  rj.info.parent_link = joint.parent_link;
  rj.info.child_link = joint.child_link;
  rj.origin = joint.origin;
  rj.axis = joint.axis;
  rj.fixed = joint.type == JointType::kFixed;
  if (rj.fixed) return rj;
  rj.info.type = joint.type == JointType::kPrismatic ? sixdof_sim::JointType::kPrismatic
                                                     : sixdof_sim::JointType::kRevolute;
  rj.info.bounded = joint.limits.bounded;
  rj.info.lower = joint.limits.lower;
  rj.info.upper = joint.limits.upper;
  rj.info.max_velocity = joint.limits.velocity;
  rj.info.max_effort = joint.limits.effort;
  if (!(rj.info.max_effort > 0.0)) {
    throw std::invalid_argument("URDF joint '" + joint.name + "': <limit effort> must be > 0 (servo bound)");
  }
  rj.info.damping = joint.damping;
  rj.info.friction = joint.friction;
  if (rj.info.damping < 0.0 || rj.info.friction < 0.0) {
    throw std::invalid_argument("URDF joint '" + joint.name + "': negative damping or friction");
  }
  if (joint.mimic) {
    rj.info.mimic_of = joint.mimic->joint;
    rj.info.mimic_multiplier = joint.mimic->multiplier;
    rj.info.mimic_offset = joint.mimic->offset;
  }
  if (child.mass <= 0.0) {
    throw std::invalid_argument("URDF link '" + child.name + "' cannot be simulated: it is moved by joint '" +
                                joint.name + "' but has no <inertial> with mass > 0 (only links on fixed joints may "
                                "go without); run the robot from the config package `rosrun sixdof_core "
                                "setup_assistant` generates, whose URDF has the missing inertias computed");
  }
  return rj;
}

}  // namespace

const tinyxml2::XMLElement& parseUrdfRobot(tinyxml2::XMLDocument& doc, const std::string& urdf_xml) {
  if (doc.Parse(urdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::invalid_argument(std::string("URDF is not valid XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) throw std::invalid_argument("URDF has no <robot> element");
  return *robot;
}

const tinyxml2::XMLElement* findGazeboPlugin(const tinyxml2::XMLElement& robot, const std::string& name) {
  const tinyxml2::XMLElement* plugin = nullptr;
  for (const tinyxml2::XMLElement* gazebo = robot.FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    for (const tinyxml2::XMLElement* p = gazebo->FirstChildElement("plugin"); p != nullptr;
         p = p->NextSiblingElement("plugin")) {
      const char* plugin_name = p->Attribute("name");
      if (plugin_name == nullptr || plugin_name != name) continue;
      if (plugin != nullptr) throw std::invalid_argument("URDF has more than one " + name + " plugin");
      plugin = p;
    }
  }
  return plugin;
}

RobotDescription describeRobot(const sixdof_core::RobotModel& model, const std::string& urdf_xml) {
  RobotDescription description;
  description.name = model.name();
  description.root_link = model.rootLink();
  // The <gazebo> extensions, all from one parse of the text.
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement& robot = parseUrdfRobot(doc, urdf_xml);
  description.grasp_fix = readGraspFixPlugin(robot);
  const std::map<std::string, double> friction = readLinkFriction(robot);
  for (const auto& entry : friction) {
    if (model.linkIndex(entry.first) < 0) {
      throw std::invalid_argument("URDF <gazebo reference=\"" + entry.first + "\">: no such link");
    }
  }
  // The core's order: joints()[i] is the parent joint of links()[i + 1].
  for (size_t i = 0; i < model.links().size(); ++i) {
    RobotLink link = describeLink(model.links()[i]);
    const auto f = friction.find(link.name);
    if (f != friction.end()) link.friction = f->second;
    if (i > 0) description.joints.push_back(describeJoint(model.joints()[i - 1], link));
    description.links.push_back(std::move(link));
  }
  return description;
}

RobotDescription parseRobotDescription(const std::string& urdf_xml, const sixdof_core::PackageResolver& resolver) {
  try {
    const sixdof_core::RobotModel model(urdf_xml, "", resolver);
    return describeRobot(model, urdf_xml);
  } catch (const sixdof_core::RobotModelError& e) {
    throw std::invalid_argument(e.what());
  }
}

}  // namespace sixdof_sim
