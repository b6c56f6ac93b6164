// RobotModel (URDF + SRDF) and its plain parts: joints, links, shapes, groups, named states.
#include <cstdlib>
#include <filesystem>
#include <map>

#include "common.h"

namespace sixdof_core::python {

namespace {

// Package directories first, then the search roots (ROS_PACKAGE_PATH when none are given). Relative directories
// are taken from the current directory, as Python's open() takes paths.
PackageResolver makeResolver(const std::map<std::string, std::string>& package_dirs,
                             const std::optional<std::vector<std::string>>& search_roots) {
  PackageResolver resolver;
  if (search_roots) {
    std::vector<std::string> roots;
    for (const auto& root : *search_roots) roots.push_back(std::filesystem::absolute(root).string());
    resolver = PackageResolver::fromSearchRoots(roots);
  } else {
    const char* path = std::getenv("ROS_PACKAGE_PATH");
    resolver = PackageResolver::fromRosPackagePath(path ? path : "");
  }
  for (const auto& [package, directory] : package_dirs) {
    resolver.addPackage(package, std::filesystem::absolute(directory).string());
  }
  return resolver;
}

template <class T>
std::vector<std::string> names(const std::vector<T>& items) {
  std::vector<std::string> out;
  for (const auto& item : items) out.push_back(item.name);
  return out;
}

const JointGroup& findGroup(const RobotModel& model, const std::string& name) {
  if (const JointGroup* group = model.findGroup(name)) return *group;
  std::string known;
  for (const auto& group : model.groups()) known += (known.empty() ? "'" : ", '") + group.name + "'";
  throw std::invalid_argument("unknown group '" + name + "' (known: " + (known.empty() ? "none" : known) + ")");
}

Shape makeShape(ShapeType type) {
  Shape shape;
  shape.type = type;
  return shape;
}

void bindShapes(py::module_& m) {
  py::enum_<ShapeType>(m, "ShapeType", "The kinds of Shape: shape_msgs/SolidPrimitive's primitives and meshes.")
      .value("BOX", ShapeType::kBox)
      .value("SPHERE", ShapeType::kSphere)
      .value("CYLINDER", ShapeType::kCylinder)
      .value("MESH", ShapeType::kMesh);

  py::class_<Shape>(m, "Shape", "A box, sphere, cylinder (along its z axis) or triangle mesh.")
      .def_static(
          "box",
          [](const Eigen::Vector3d& size) {
            auto s = makeShape(ShapeType::kBox);
            s.box_size = size;
            return s;
          },
          py::arg("size"), "A box of full extents size = (x, y, z), metres.")
      .def_static(
          "sphere",
          [](double radius) {
            auto s = makeShape(ShapeType::kSphere);
            s.radius = radius;
            return s;
          },
          py::arg("radius"))
      .def_static(
          "cylinder",
          [](double radius, double length) {
            auto s = makeShape(ShapeType::kCylinder);
            s.radius = radius;
            s.length = length;
            return s;
          },
          py::arg("radius"), py::arg("length"), "A cylinder along its z axis, centred on its origin.")
      .def_static(
          "mesh",
          [](const std::string& path, const Eigen::Vector3d& scale) {
            auto s = makeShape(ShapeType::kMesh);
            s.mesh_resource = s.mesh_path = path;
            s.mesh_scale = scale;
            return s;
          },
          py::arg("path"), py::arg("scale") = Eigen::Vector3d::Ones(),
          "A mesh file (STL, OBJ, DAE: what assimp reads) by its path, scaled per axis.")
      .def_readonly("type", &Shape::type)
      .def_readonly("box_size", &Shape::box_size)
      .def_readonly("radius", &Shape::radius)
      .def_readonly("length", &Shape::length)
      .def_readonly("mesh_resource", &Shape::mesh_resource, "The mesh's URI or path as written.")
      .def_readonly("mesh_path", &Shape::mesh_path, "The file it resolves to.")
      .def_readonly("mesh_scale", &Shape::mesh_scale);

  py::class_<PlacedShape>(m, "PlacedShape", "A shape placed in a frame (a link's, an object's).")
      .def(py::init([](const Shape& shape, const Eigen::Isometry3d& origin) {
             return PlacedShape{shape, origin};
           }),
           py::arg("shape"), identityPose("origin"))
      .def_readonly("shape", &PlacedShape::shape)
      .def_readonly("origin", &PlacedShape::origin);
}

void bindJointsAndLinks(py::module_& m) {
  py::enum_<JointType>(m, "JointType")
      .value("FIXED", JointType::kFixed)
      .value("REVOLUTE", JointType::kRevolute)
      .value("CONTINUOUS", JointType::kContinuous)
      .value("PRISMATIC", JointType::kPrismatic);

  py::class_<JointLimits>(m, "JointLimits",
                          "Limits of a joint. A continuous joint is unbounded (bounded False) with the nominal "
                          "lower/upper -pi/pi.")
      .def_readonly("bounded", &JointLimits::bounded)
      .def_readonly("lower", &JointLimits::lower)
      .def_readonly("upper", &JointLimits::upper)
      .def_readonly("velocity", &JointLimits::velocity)
      .def_readonly("effort", &JointLimits::effort);

  py::class_<MimicInfo>(m, "MimicInfo", "value = multiplier * joint + offset.")
      .def_readonly("joint", &MimicInfo::joint)
      .def_readonly("multiplier", &MimicInfo::multiplier)
      .def_readonly("offset", &MimicInfo::offset);

  py::class_<JointModel>(m, "JointModel", "A URDF joint as the model reads it.")
      .def_readonly("name", &JointModel::name)
      .def_readonly("type", &JointModel::type)
      .def_readonly("parent_link", &JointModel::parent_link)
      .def_readonly("child_link", &JointModel::child_link)
      .def_readonly("origin", &JointModel::origin, "The child frame at zero, in the parent's.")
      .def_readonly("axis", &JointModel::axis, "Unit axis in the joint (child) frame.")
      .def_readonly("limits", &JointModel::limits)
      .def_readonly("damping", &JointModel::damping)
      .def_readonly("friction", &JointModel::friction)
      .def_readonly("mimic", &JointModel::mimic)
      .def_readonly("variable_index", &JointModel::variable_index, "Index in RobotState.positions; -1 if none.")
      .def_property_readonly("is_active", &JointModel::isActive, "Not fixed, not a mimic joint: a variable.")
      .def_property_readonly("is_multi_turn", &JointModel::isMultiTurn);

  py::class_<LinkInertial>(m, "LinkInertial", "A link's mass, centre-of-mass frame and inertia about it.")
      .def_readonly("mass", &LinkInertial::mass)
      .def_readonly("origin", &LinkInertial::origin, "The inertial frame in the link frame.")
      .def_readonly("inertia", &LinkInertial::inertia, "3x3, about the centre of mass, inertial-frame axes.");

  py::class_<LinkModel>(m, "LinkModel", "A URDF link: its place in the tree, collision shapes and inertial.")
      .def_readonly("name", &LinkModel::name)
      .def_readonly("parent_joint", &LinkModel::parent_joint, "Index into RobotModel.joints; -1 for the root.")
      .def_readonly("parent_link", &LinkModel::parent_link, "Index into RobotModel.links; -1 for the root.")
      .def_property_readonly(
          "collision_shapes", [](const LinkModel& l) { return l.collision.shapes; }, "In the link frame.")
      .def_readonly("inertial", &LinkModel::inertial);
}

void bindSemantics(py::module_& m) {
  py::class_<JointGroup>(m, "JointGroup", "An SRDF planning group, expanded (chains and subgroups), in model order.")
      .def_readonly("name", &JointGroup::name)
      .def_readonly("joints", &JointGroup::joints, "Every joint, fixed and mimic ones included.")
      .def_readonly("active_joints", &JointGroup::active_joints, "The group's variables.")
      .def_readonly("links", &JointGroup::links)
      .def_readonly("subgroups", &JointGroup::subgroups)
      .def_readonly("chain_base", &JointGroup::chain_base, "Set when declared as a <chain>.")
      .def_readonly("chain_tip", &JointGroup::chain_tip)
      .def_property_readonly("is_chain", &JointGroup::isChain);

  py::class_<GroupState>(m, "GroupState", "An SRDF group_state: joint name -> position.")
      .def_readonly("name", &GroupState::name)
      .def_readonly("group", &GroupState::group)
      .def_readonly("values", &GroupState::values);

  py::class_<EndEffector>(m, "EndEffector", "An SRDF end effector: a group attached to a parent link.")
      .def_readonly("name", &EndEffector::name)
      .def_readonly("parent_link", &EndEffector::parent_link)
      .def_readonly("group", &EndEffector::group)
      .def_readonly("parent_group", &EndEffector::parent_group);

  py::class_<VirtualJoint>(m, "VirtualJoint", "An SRDF virtual joint (recorded; it adds no variables).")
      .def_readonly("name", &VirtualJoint::name)
      .def_readonly("type", &VirtualJoint::type)
      .def_readonly("parent_frame", &VirtualJoint::parent_frame)
      .def_readonly("child_link", &VirtualJoint::child_link);

  py::class_<DisabledCollisionPair>(m, "DisabledCollisionPair", "An SRDF disable_collisions entry.")
      .def_readonly("link1", &DisabledCollisionPair::link1)
      .def_readonly("link2", &DisabledCollisionPair::link2)
      .def_readonly("reason", &DisabledCollisionPair::reason);
}

}  // namespace

void bindModel(py::module_& m) {
  bindShapes(m);
  bindJointsAndLinks(m);
  bindSemantics(m);

  py::class_<RobotModel, ModelPtr>(
      m, "RobotModel",
      "The immutable robot model: the URDF's links and joints with the SRDF's groups, named states and end "
      "effectors. Links are in breadth-first order from the root (siblings in document order), joints in the same "
      "order, the variables (active joints) in that order.")
      .def(py::init([](const std::string& urdf, const std::string& srdf,
                       const std::map<std::string, std::string>& package_dirs,
                       const std::optional<std::vector<std::string>>& search_roots) {
             return std::make_shared<RobotModel>(urdf, srdf, makeResolver(package_dirs, search_roots));
           }),
           py::arg("urdf"), py::arg("srdf") = "", py::arg("package_dirs") = std::map<std::string, std::string>(),
           py::arg("search_roots") = py::none(),
           "From URDF and SRDF XML text (an empty SRDF: no groups). Mesh URIs package://pkg/... resolve in "
           "package_dirs ({package: directory}) first, then in the search_roots (default: ROS_PACKAGE_PATH). "
           "Raises RobotModelError naming the problem.")
      .def_static(
          "from_files",
          [](const std::string& urdf_path, const std::string& srdf_path,
             const std::map<std::string, std::string>& package_dirs,
             const std::optional<std::vector<std::string>>& search_roots) {
            const std::string srdf = srdf_path.empty() ? std::string() : readTextFile(srdf_path);
            return std::make_shared<RobotModel>(readTextFile(urdf_path), srdf,
                                                makeResolver(package_dirs, search_roots));
          },
          py::arg("urdf_path"), py::arg("srdf_path") = "",
          py::arg("package_dirs") = std::map<std::string, std::string>(), py::arg("search_roots") = py::none(),
          "The same from files.")
      .def_property_readonly("name", &RobotModel::name)
      .def_property_readonly("root_link", &RobotModel::rootLink)
      .def_property_readonly("links", &RobotModel::links)
      .def_property_readonly("joints", &RobotModel::joints)
      .def_property_readonly("link_names", [](const RobotModel& r) { return names(r.links()); })
      .def_property_readonly("joint_names", [](const RobotModel& r) { return names(r.joints()); })
      .def_property_readonly("variable_names", &RobotModel::variableNames, "The active joints, in state order.")
      .def_property_readonly("variable_count", &RobotModel::variableCount)
      .def("link", &RobotModel::link, py::arg("name"), py::return_value_policy::reference_internal,
           "Raises ValueError for an unknown link.")
      .def("joint", &RobotModel::joint, py::arg("name"), py::return_value_policy::reference_internal,
           "Raises ValueError for an unknown joint.")
      .def("default_positions", &RobotModel::defaultPositions, "0 where within limits, else the middle of the range.")
      .def_property_readonly("groups", &RobotModel::groups)
      .def_property_readonly("group_names", [](const RobotModel& r) { return names(r.groups()); })
      .def("group", &findGroup, py::arg("name"), py::return_value_policy::reference_internal,
           "Raises ValueError naming the known groups.")
      .def_property_readonly("group_states", &RobotModel::groupStates)
      .def_property_readonly("end_effectors", &RobotModel::endEffectors)
      .def_property_readonly("virtual_joints", &RobotModel::virtualJoints)
      .def_property_readonly("passive_joints", &RobotModel::passiveJoints)
      .def_property_readonly("disabled_collision_pairs", &RobotModel::disabledCollisionPairs)
      .def("__repr__", [](const RobotModel& r) {
        return "<RobotModel '" + r.name() + "': " + std::to_string(r.links().size()) + " links, " +
               std::to_string(r.variableCount()) + " variables, " + std::to_string(r.groups().size()) + " groups>";
      });

  m.def(
      "find_package",
      [](const std::string& package, const std::optional<std::vector<std::string>>& search_roots) {
        return makeResolver({}, search_roots).packageDirectory(package);
      },
      py::arg("package"), py::arg("search_roots") = py::none(),
      "The directory of a ROS package (its package.xml names it) below the search roots (default: "
      "ROS_PACKAGE_PATH), as package:// URIs resolve. Raises RobotModelError when none holds it.");
}

}  // namespace sixdof_core::python
