#include "sixdof_core/robot_model.h"

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>

#include <console_bridge/console.h>

#include "sixdof_core/result.h"

namespace sixdof_core {

namespace fs = std::filesystem;

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

std::string requiredAttribute(const tinyxml2::XMLElement* e, const char* attribute, const std::string& context) {
  const char* value = e->Attribute(attribute);
  if (!value || std::string(value).empty()) {
    throw RobotModelError("SRDF: <" + std::string(e->Name()) + "> " + context + "has no '" + attribute +
                          "' attribute (line " + std::to_string(e->GetLineNum()) + ")");
  }
  return value;
}

std::string readPackageName(const fs::path& package_xml) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(package_xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return "";
  const auto* name = doc.RootElement()->FirstChildElement("name");
  return name && name->GetText() ? std::string(name->GetText()) : "";
}

// Finds the directory of `package` below root, at most `depth` levels deep, skipping hidden folders.
std::optional<fs::path> findPackage(const fs::path& root, const std::string& package, int depth) {
  std::error_code ec;
  if (fs::exists(root / "package.xml", ec)) {
    // A package does not contain other packages.
    if (readPackageName(root / "package.xml") == package) return root;
    return std::nullopt;
  }
  if (depth == 0) return std::nullopt;
  if (fs::exists(root / package / "package.xml", ec) && readPackageName(root / package / "package.xml") == package) {
    return root / package;
  }
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const auto& entry = *it;
    if (!entry.is_directory(ec) || entry.path().filename().string().front() == '.') continue;
    if (auto found = findPackage(entry.path(), package, depth - 1)) return found;
  }
  return std::nullopt;
}

}  // namespace

const char* toString(JointType type) {
  static constexpr const char* kNames[] = {"fixed", "revolute", "continuous", "prismatic"};
  return enumName<JointType::kPrismatic>(type, kNames, "");
}

bool JointModel::isMultiTurn() const {
  if (type == JointType::kContinuous) return true;
  return type == JointType::kRevolute && limits.upper - limits.lower > 2.0 * M_PI;
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RobotModelError("cannot read file '" + path + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// ---------------------------------------------------------------------------------------------------
// PackageResolver

PackageResolver PackageResolver::fromSearchRoots(const std::vector<std::string>& roots) {
  PackageResolver resolver;
  resolver.roots_ = roots;
  return resolver;
}

PackageResolver PackageResolver::fromRosPackagePath(const std::string& ros_package_path) {
  std::vector<std::string> roots;
  std::stringstream in(ros_package_path);
  std::string root;
  while (std::getline(in, root, ':')) {
    if (!root.empty()) roots.push_back(root);
  }
  return fromSearchRoots(roots);
}

PackageResolver PackageResolver::fromMap(const std::map<std::string, std::string>& package_dirs) {
  PackageResolver resolver;
  resolver.package_dirs_ = package_dirs;
  return resolver;
}

PackageResolver& PackageResolver::addPackage(const std::string& package, const std::string& directory) {
  package_dirs_[package] = directory;
  return *this;
}

std::string PackageResolver::packageDirectory(const std::string& package) const {
  auto it = package_dirs_.find(package);
  if (it != package_dirs_.end()) return it->second;
  for (const auto& root : roots_) {
    if (auto found = findPackage(root, package, 3)) return found->string();
  }
  std::string where;
  for (const auto& root : roots_) where += (where.empty() ? "" : ":") + root;
  for (const auto& [name, dir] : package_dirs_) where += (where.empty() ? "" : ", ") + name + "=" + dir;
  throw RobotModelError("package '" + package + "' not found (searched: " + (where.empty() ? "nothing" : where) +
                        ")");
}

std::string PackageResolver::resolve(const std::string& uri) const {
  fs::path path;
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (uri.rfind(package_scheme, 0) == 0) {
    const std::string rest = uri.substr(package_scheme.size());
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) throw RobotModelError("malformed package URI '" + uri + "'");
    path = fs::path(packageDirectory(rest.substr(0, slash))) / rest.substr(slash + 1);
  } else if (uri.rfind(file_scheme, 0) == 0) {
    path = uri.substr(file_scheme.size());
  } else {
    path = uri;
  }
  if (!path.is_absolute()) throw RobotModelError("mesh '" + uri + "' is neither a package URI nor an absolute path");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw RobotModelError("mesh '" + uri + "' resolves to '" + path.string() + "', which does not exist");
  }
  return path.lexically_normal().string();
}

// ---------------------------------------------------------------------------------------------------
// RobotModel

RobotModel::RobotModel(const std::string& urdf_xml, const std::string& srdf_xml, const PackageResolver& resolver) {
  parseUrdf(urdf_xml, resolver);
  if (!srdf_xml.empty()) parseSrdf(srdf_xml);
}

std::shared_ptr<const RobotModel> RobotModel::fromFiles(const std::string& urdf_path, const std::string& srdf_path,
                                                        const PackageResolver& resolver) {
  return std::make_shared<const RobotModel>(readTextFile(urdf_path), readTextFile(srdf_path), resolver);
}

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
      switch (ujoint.type) {
        case urdf::Joint::FIXED:
          joint.type = JointType::kFixed;
          break;
        case urdf::Joint::REVOLUTE:
          joint.type = JointType::kRevolute;
          break;
        case urdf::Joint::CONTINUOUS:
          joint.type = JointType::kContinuous;
          break;
        case urdf::Joint::PRISMATIC:
          joint.type = JointType::kPrismatic;
          break;
        default:
          throw RobotModelError("URDF: joint '" + ujoint.name + "' has an unsupported type (only fixed, revolute, " +
                                "continuous and prismatic joints are supported)");
      }
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

void RobotModel::parseSrdf(const std::string& srdf_xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(srdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw RobotModelError(std::string("SRDF: XML error: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") throw RobotModelError("SRDF: root element is not <robot>");
  const std::string srdf_name = requiredAttribute(robot, "name", "");
  if (srdf_name != name_) {
    throw RobotModelError("SRDF: robot name '" + srdf_name + "' does not match the URDF's '" + name_ + "'");
  }
  auto check_link = [&](const std::string& link, const std::string& context) {
    if (linkIndex(link) < 0) throw RobotModelError("SRDF: " + context + " refers to unknown link '" + link + "'");
  };
  auto check_joint = [&](const std::string& joint, const std::string& context) {
    if (jointIndex(joint) < 0) throw RobotModelError("SRDF: " + context + " refers to unknown joint '" + joint + "'");
  };

  // Groups are collected first, then expanded, because subgroups may be declared after their users.
  struct RawGroup {
    std::set<int> joints;
    std::set<int> links;
  };
  std::map<std::string, RawGroup> raw;
  std::vector<std::pair<const tinyxml2::XMLElement*, std::string>> state_elements;
  for (const auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string element = e->Name();
    if (element == "group") {
      JointGroup group;
      group.name = requiredAttribute(e, "name", "");
      if (findGroup(group.name)) throw RobotModelError("SRDF: group '" + group.name + "' is declared twice");
      const std::string context = "group '" + group.name + "'";
      RawGroup& contents = raw[group.name];
      for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
        const std::string child = c->Name();
        if (child == "joint") {
          const std::string joint = requiredAttribute(c, "name", "in " + context + " ");
          check_joint(joint, context);
          contents.joints.insert(jointIndex(joint));
          contents.links.insert(linkIndex(joints_[jointIndex(joint)].child_link));
        } else if (child == "link") {
          const std::string link = requiredAttribute(c, "name", "in " + context + " ");
          check_link(link, context);
          contents.links.insert(linkIndex(link));
          if (links_[linkIndex(link)].parent_joint >= 0) contents.joints.insert(links_[linkIndex(link)].parent_joint);
        } else if (child == "chain") {
          if (group.isChain()) throw RobotModelError("SRDF: " + context + " has more than one <chain>");
          group.chain_base = requiredAttribute(c, "base_link", "in " + context + " ");
          group.chain_tip = requiredAttribute(c, "tip_link", "in " + context + " ");
          check_link(group.chain_base, context + " chain");
          check_link(group.chain_tip, context + " chain");
          std::vector<int> chain;
          try {
            chain = chainJoints(group.chain_base, group.chain_tip);
          } catch (const RobotModelError& error) {
            throw RobotModelError("SRDF: " + context + ": " + error.what());
          }
          for (int j : chain) {
            contents.joints.insert(j);
            contents.links.insert(linkIndex(joints_[j].child_link));
          }
        } else if (child == "group") {
          group.subgroups.push_back(requiredAttribute(c, "name", "in " + context + " "));
        } else {
          throw RobotModelError("SRDF: " + context + " has an unknown element <" + child + ">");
        }
      }
      groups_.push_back(group);
    } else if (element == "group_state") {
      state_elements.emplace_back(e, requiredAttribute(e, "name", ""));
    } else if (element == "end_effector") {
      EndEffector eef;
      eef.name = requiredAttribute(e, "name", "");
      eef.parent_link = requiredAttribute(e, "parent_link", "'" + eef.name + "' ");
      eef.group = requiredAttribute(e, "group", "'" + eef.name + "' ");
      if (const char* parent_group = e->Attribute("parent_group")) eef.parent_group = parent_group;
      check_link(eef.parent_link, "end effector '" + eef.name + "'");
      end_effectors_.push_back(eef);
    } else if (element == "virtual_joint") {
      VirtualJoint vj;
      vj.name = requiredAttribute(e, "name", "");
      vj.type = requiredAttribute(e, "type", "'" + vj.name + "' ");
      vj.parent_frame = requiredAttribute(e, "parent_frame", "'" + vj.name + "' ");
      vj.child_link = requiredAttribute(e, "child_link", "'" + vj.name + "' ");
      if (vj.type != "fixed" && vj.type != "floating" && vj.type != "planar") {
        throw RobotModelError("SRDF: virtual joint '" + vj.name + "' has unknown type '" + vj.type + "'");
      }
      check_link(vj.child_link, "virtual joint '" + vj.name + "'");
      if (vj.child_link != rootLink()) {
        throw RobotModelError("SRDF: virtual joint '" + vj.name + "' attaches '" + vj.child_link +
                              "', which is not the URDF root link '" + rootLink() + "'");
      }
      virtual_joints_.push_back(vj);
    } else if (element == "passive_joint") {
      const std::string joint = requiredAttribute(e, "name", "");
      check_joint(joint, "passive joint");
      passive_joints_.push_back(joint);
    } else if (element == "disable_collisions") {
      DisabledCollisionPair pair;
      pair.link1 = requiredAttribute(e, "link1", "");
      pair.link2 = requiredAttribute(e, "link2", "");
      if (const char* reason = e->Attribute("reason")) pair.reason = reason;
      check_link(pair.link1, "disable_collisions");
      check_link(pair.link2, "disable_collisions");
      disabled_collisions_.push_back(pair);
    } else {
      throw RobotModelError("SRDF: unknown element <" + element + "> (line " + std::to_string(e->GetLineNum()) + ")");
    }
  }

  // Expand subgroups (depth first, rejecting cycles and unknown names).
  std::map<std::string, int> visit_state;  // 1 = in progress, 2 = done
  std::function<void(const std::string&)> expand = [&](const std::string& name) {
    if (visit_state[name] == 2) return;
    if (visit_state[name] == 1) throw RobotModelError("SRDF: group '" + name + "' contains itself via subgroups");
    visit_state[name] = 1;
    const JointGroup* group = findGroup(name);
    for (const auto& sub : group->subgroups) {
      if (!findGroup(sub)) {
        throw RobotModelError("SRDF: group '" + name + "' refers to unknown subgroup '" + sub + "'");
      }
      expand(sub);
      raw[name].joints.insert(raw[sub].joints.begin(), raw[sub].joints.end());
      raw[name].links.insert(raw[sub].links.begin(), raw[sub].links.end());
    }
    visit_state[name] = 2;
  };
  for (auto& group : groups_) {
    expand(group.name);
    // Joint and link indices follow topological order, so the sets are already in model order.
    for (int j : raw[group.name].joints) {
      group.joints.push_back(joints_[j].name);
      if (joints_[j].isActive()) group.active_joints.push_back(joints_[j].name);
    }
    for (int l : raw[group.name].links) group.links.push_back(links_[l].name);
    if (group.joints.empty() && group.links.empty()) {
      throw RobotModelError("SRDF: group '" + group.name + "' is empty");
    }
  }

  for (const auto& eef : end_effectors_) {
    if (!findGroup(eef.group)) {
      throw RobotModelError("SRDF: end effector '" + eef.name + "' refers to unknown group '" + eef.group + "'");
    }
    if (!eef.parent_group.empty() && !findGroup(eef.parent_group)) {
      throw RobotModelError("SRDF: end effector '" + eef.name + "' refers to unknown parent group '" +
                            eef.parent_group + "'");
    }
  }

  for (const auto& [e, name] : state_elements) {
    GroupState state;
    state.name = name;
    state.group = requiredAttribute(e, "group", "'" + name + "' ");
    const std::string context = "group_state '" + name + "' of group '" + state.group + "'";
    const JointGroup* group = findGroup(state.group);
    if (!group) throw RobotModelError("SRDF: group_state '" + name + "' refers to unknown group '" + state.group + "'");
    if (findGroupState(state.group, name)) throw RobotModelError("SRDF: " + context + " is declared twice");
    for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      if (std::string(c->Name()) != "joint") {
        throw RobotModelError("SRDF: " + context + " has an unknown element <" + c->Name() + ">");
      }
      const std::string joint_name = requiredAttribute(c, "name", "in " + context + " ");
      check_joint(joint_name, context);
      if (std::find(group->joints.begin(), group->joints.end(), joint_name) == group->joints.end()) {
        throw RobotModelError("SRDF: " + context + " sets joint '" + joint_name + "', which is not in the group");
      }
      const std::string text = requiredAttribute(c, "value", "'" + joint_name + "' in " + context + " ");
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
        throw RobotModelError("SRDF: " + context + ": value '" + text + "' of joint '" + joint_name +
                              "' is not a number");
      }
      const JointModel& joint = joints_[jointIndex(joint_name)];
      if (joint.limits.bounded && joint.type != JointType::kFixed &&
          (value < joint.limits.lower || value > joint.limits.upper)) {
        throw RobotModelError("SRDF: " + context + ": value " + text + " of joint '" + joint_name +
                              "' is outside its limits [" + std::to_string(joint.limits.lower) + ", " +
                              std::to_string(joint.limits.upper) + "]");
      }
      state.values[joint_name] = value;
    }
    group_states_.push_back(state);
  }
}

int RobotModel::linkIndex(const std::string& name) const {
  auto it = link_index_.find(name);
  return it == link_index_.end() ? -1 : it->second;
}

int RobotModel::jointIndex(const std::string& name) const {
  auto it = joint_index_.find(name);
  return it == joint_index_.end() ? -1 : it->second;
}

const LinkModel& RobotModel::link(const std::string& name) const {
  const int index = linkIndex(name);
  if (index < 0) throw std::out_of_range("unknown link '" + name + "'");
  return links_[index];
}

const JointModel& RobotModel::joint(const std::string& name) const {
  const int index = jointIndex(name);
  if (index < 0) throw std::out_of_range("unknown joint '" + name + "'");
  return joints_[index];
}

Eigen::VectorXd RobotModel::defaultPositions() const {
  Eigen::VectorXd q(variableCount());
  for (size_t v = 0; v < variableCount(); ++v) {
    const auto& limits = variableJoint(v).limits;
    q[v] = (0.0 >= limits.lower && 0.0 <= limits.upper) ? 0.0 : 0.5 * (limits.lower + limits.upper);
  }
  return q;
}

std::vector<int> RobotModel::chainJoints(const std::string& base_link, const std::string& tip_link) const {
  const int base = linkIndex(base_link);
  int link = linkIndex(tip_link);
  if (base < 0) throw RobotModelError("unknown link '" + base_link + "'");
  if (link < 0) throw RobotModelError("unknown link '" + tip_link + "'");
  std::vector<int> joints;
  while (link != base) {
    if (link < 0 || links_[link].parent_joint < 0) {
      throw RobotModelError("link '" + tip_link + "' is not a descendant of '" + base_link + "'");
    }
    joints.push_back(links_[link].parent_joint);
    link = links_[link].parent_link;
  }
  std::reverse(joints.begin(), joints.end());
  return joints;
}

const JointGroup* RobotModel::findGroup(const std::string& name) const {
  for (const auto& group : groups_) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

const GroupState* RobotModel::findGroupState(const std::string& group, const std::string& name) const {
  for (const auto& state : group_states_) {
    if (state.group == group && state.name == name) return &state;
  }
  return nullptr;
}

std::vector<LinkGeometry> RobotModel::collisionGeometry() const {
  std::vector<LinkGeometry> geometry;
  for (const auto& link : links_) {
    if (!link.collision.shapes.empty()) geometry.push_back(link.collision);
  }
  return geometry;
}

// ---------------------------------------------------------------------------------------------------
// RobotState

RobotState::RobotState(RobotModelConstPtr model) : model_(std::move(model)) {
  if (!model_) throw std::invalid_argument("RobotState needs a robot model");
  joint_values_.assign(model_->joints().size(), 0.0);
  link_transforms_.assign(model_->links().size(), Eigen::Isometry3d::Identity());
  positions_ = model_->defaultPositions();
  update();
}

void RobotState::setPositions(const Eigen::VectorXd& positions) {
  if (static_cast<size_t>(positions.size()) != model_->variableCount()) {
    throw std::invalid_argument("RobotState::setPositions: " + std::to_string(positions.size()) + " values for " +
                                std::to_string(model_->variableCount()) + " variables");
  }
  if (!positions.allFinite()) throw std::invalid_argument("RobotState::setPositions: non-finite joint value");
  positions_ = positions;
  update();
}

double RobotState::jointPosition(const std::string& joint) const {
  const int index = model_->jointIndex(joint);
  if (index < 0) throw std::invalid_argument("unknown joint '" + joint + "'");
  return joint_values_[index];
}

void RobotState::setJointPosition(const std::string& joint, double value) {
  const int index = model_->jointIndex(joint);
  if (index < 0) throw std::invalid_argument("unknown joint '" + joint + "'");
  const JointModel& model = model_->joints()[index];
  if (!model.isActive()) throw std::invalid_argument("joint '" + joint + "' is fixed or a mimic joint");
  if (!std::isfinite(value)) throw std::invalid_argument("non-finite value for joint '" + joint + "'");
  positions_[model.variable_index] = value;
  update();
}

Eigen::VectorXd RobotState::groupPositions(const std::string& group) const {
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  Eigen::VectorXd values(g->active_joints.size());
  for (size_t i = 0; i < g->active_joints.size(); ++i) {
    values[i] = positions_[model_->joint(g->active_joints[i]).variable_index];
  }
  return values;
}

void RobotState::setGroupPositions(const std::string& group, const Eigen::VectorXd& values) {
  const JointGroup* g = model_->findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  if (static_cast<size_t>(values.size()) != g->active_joints.size()) {
    throw std::invalid_argument("group '" + group + "' has " + std::to_string(g->active_joints.size()) +
                                " variables, got " + std::to_string(values.size()) + " values");
  }
  if (!values.allFinite()) throw std::invalid_argument("non-finite value for group '" + group + "'");
  for (size_t i = 0; i < g->active_joints.size(); ++i) {
    positions_[model_->joint(g->active_joints[i]).variable_index] = values[i];
  }
  update();
}

void RobotState::setVariablePositions(const std::vector<int>& indices, const Eigen::VectorXd& values) {
  if (static_cast<size_t>(values.size()) != indices.size()) {
    throw std::invalid_argument("RobotState::setVariablePositions: " + std::to_string(values.size()) +
                                " values for " + std::to_string(indices.size()) + " indices");
  }
  if (!values.allFinite()) throw std::invalid_argument("RobotState::setVariablePositions: non-finite value");
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < 0 || indices[i] >= positions_.size()) {
      throw std::invalid_argument("RobotState::setVariablePositions: variable index " + std::to_string(indices[i]) +
                                  " out of range");
    }
    positions_[indices[i]] = values[i];
  }
  update();
}

bool RobotState::setToNamedState(const std::string& group, const std::string& state) {
  const GroupState* s = model_->findGroupState(group, state);
  if (!s) return false;
  for (const auto& [joint, value] : s->values) {
    const JointModel& model = model_->joint(joint);
    // Values of mimic joints in a state follow from their source joint.
    if (model.isActive()) positions_[model.variable_index] = value;
  }
  update();
  return true;
}

const Eigen::Isometry3d& RobotState::linkTransform(const std::string& link) const {
  const int index = model_->linkIndex(link);
  if (index < 0) throw std::out_of_range("unknown link '" + link + "'");
  return link_transforms_[index];
}

bool RobotState::satisfiesBounds(double tolerance) const {
  for (size_t v = 0; v < model_->variableCount(); ++v) {
    const auto& limits = model_->variableJoint(v).limits;
    if (!limits.bounded) continue;
    if (positions_[v] < limits.lower - tolerance || positions_[v] > limits.upper + tolerance) return false;
  }
  return true;
}

void RobotState::update() {
  const auto& joints = model_->joints();
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].isActive()) joint_values_[j] = positions_[joints[j].variable_index];
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].mimic) {
      const auto& mimic = *joints[j].mimic;
      joint_values_[j] = mimic.multiplier * joint_values_[mimic.joint_index] + mimic.offset;
    }
  }
  const auto& links = model_->links();
  link_transforms_[0] = Eigen::Isometry3d::Identity();
  for (size_t l = 1; l < links.size(); ++l) {
    const JointModel& joint = joints[links[l].parent_joint];
    Eigen::Isometry3d t = link_transforms_[links[l].parent_link] * joint.origin;
    const double value = joint_values_[links[l].parent_joint];
    switch (joint.type) {
      case JointType::kRevolute:
      case JointType::kContinuous:
        t.rotate(Eigen::AngleAxisd(value, joint.axis));
        break;
      case JointType::kPrismatic:
        t.translate(value * joint.axis);
        break;
      case JointType::kFixed:
        break;
    }
    link_transforms_[l] = t;
  }
}

}  // namespace sixdof_core
