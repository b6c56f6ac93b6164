// The collision scene: world objects (primitives and meshes), attached objects, allowed collisions, padding,
// and the queries (collision, contacts, distance) of robot states.
#include "scene.h"
#include "sixdof_core/setup_assistant.h"

namespace sixdof_core::python {

namespace {

// A scene change the core refused (SceneStatus), raised as sixdof_core.SceneError with its status.
struct SceneStatusError : std::invalid_argument {
  explicit SceneStatusError(const SceneStatus& result) : std::invalid_argument(result.message), status(result.status) {}
  SceneStatusCode status;
};

void check(const SceneStatus& result) {
  if (!result) throw SceneStatusError(result);
}

std::vector<std::pair<std::string, std::string>> disabledPairs(const RobotModel& model) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const auto& pair : model.disabledCollisionPairs()) pairs.emplace_back(pair.link1, pair.link2);
  return pairs;
}

std::vector<std::string> linkNames(const RobotModel& model) {
  std::vector<std::string> names;
  for (const auto& link : model.links()) names.push_back(link.name);
  return names;
}

void addObject(Scene& scene, const std::string& id, std::vector<PlacedShape> shapes, const Eigen::Isometry3d& pose) {
  check(scene.edit().addWorldObject(WorldObject{id, pose, std::move(shapes)}));
}

void addShape(Scene& scene, const std::string& id, const Shape& shape, const Eigen::Isometry3d& pose) {
  addObject(scene, id, {PlacedShape{shape}}, pose);
}

Shape primitive(ShapeType type) {
  Shape shape;
  shape.type = type;
  return shape;
}

// Draws states (all variables, or the group's) until one is within bounds and collision-free.
bool setToRandomValidPositions(const Scene& scene, RobotState& state, StateSampler& sampler,
                               const std::optional<std::string>& group, int max_attempts) {
  if (max_attempts < 1) throw std::invalid_argument("max_attempts must be >= 1");
  scene.checkState(state, "state");
  const JointGroup* g = group ? state.model().findGroup(*group) : nullptr;
  if (group && !g) throw std::invalid_argument("unknown group '" + *group + "'");
  RobotState candidate = state;
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    const Eigen::VectorXd sample = sampler.sample();
    if (sample.size() != candidate.positions().size()) {
      throw std::invalid_argument("the sampler was made for a model with " + std::to_string(sample.size()) +
                                  " variables, the state has " + std::to_string(candidate.positions().size()));
    }
    if (g) {
      Eigen::VectorXd values(g->active_joints.size());
      for (size_t i = 0; i < g->active_joints.size(); ++i) {
        values[i] = sample[state.model().joint(g->active_joints[i]).variable_index];
      }
      candidate.setGroupPositions(*group, values);
    } else {
      candidate.setPositions(sample);
    }
    if (candidate.satisfiesBounds() && !scene.read().isColliding(scene.linkPoses(candidate))) {
      state = candidate;
      return true;
    }
  }
  return false;
}

void bindQueryTypes(py::module_& m) {
  py::enum_<SceneStatusCode>(m, "SceneStatusCode", "Why the scene refused a change (SceneError.status).")
      .value("OK", SceneStatusCode::kOk)
      .value("UNKNOWN_NAME", SceneStatusCode::kUnknownName)
      .value("DUPLICATE_NAME", SceneStatusCode::kDuplicateName)
      .value("INVALID_SHAPE", SceneStatusCode::kInvalidShape)
      .value("MESH_LOAD_FAILED", SceneStatusCode::kMeshLoadFailed)
      .value("INVALID_VALUE", SceneStatusCode::kInvalidValue);
  static py::handle scene_error = py::exception<SceneStatusError>(m, "SceneError", PyExc_ValueError).release();
  scene_error.attr("__doc__") = "A change the collision scene refused; .status is its SceneStatusCode.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const SceneStatusError& e) {
      py::object error = scene_error(e.what());
      error.attr("status") = e.status;
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    }
  });

  py::enum_<BodyType>(m, "BodyType")
      .value("ROBOT_LINK", BodyType::kRobotLink)
      .value("ATTACHED_OBJECT", BodyType::kAttachedObject)
      .value("WORLD_OBJECT", BodyType::kWorldObject);
  py::enum_<CollisionScope>(m, "CollisionScope")
      .value("ALL", CollisionScope::kAll, "Self collision and robot vs world.")
      .value("SELF", CollisionScope::kSelf, "Robot links and attached objects among themselves.")
      .value("WORLD", CollisionScope::kWorld, "Robot links and attached objects vs world objects.");

  py::class_<BodyPair>(m, "BodyPair", "Two bodies of the scene and their kinds (a Contact's, a DistanceReport's).")
      .def_readonly("body1", &BodyPair::body1)
      .def_readonly("body2", &BodyPair::body2)
      .def_readonly("type1", &BodyPair::type1)
      .def_readonly("type2", &BodyPair::type2);
  py::class_<Contact, BodyPair>(m, "Contact",
                                "A contact between two bodies; the normal points from body1 towards body2.")
      .def_readonly("position", &Contact::position)
      .def_readonly("normal", &Contact::normal)
      .def_readonly("depth", &Contact::depth)
      .def("__repr__", [](const Contact& c) { return "<Contact '" + c.body1 + "' - '" + c.body2 + "'>"; });
  py::class_<CollisionReport>(m, "CollisionReport", "Whether a state collides, and the contacts found.")
      .def_readonly("colliding", &CollisionReport::colliding)
      .def_readonly("contacts", &CollisionReport::contacts)
      .def("__bool__", [](const CollisionReport& r) { return r.colliding; });
  py::class_<DistanceReport, BodyPair>(
      m, "DistanceReport",
      "Signed minimum distance over the pairs in scope (negative: the deepest penetration); point1/point2 are the "
      "closest points on body1/body2 in the world frame.")
      .def_readonly("found", &DistanceReport::found, "False when no pair is in scope.")
      .def_readonly("distance", &DistanceReport::distance)
      .def_readonly("point1", &DistanceReport::point1)
      .def_readonly("point2", &DistanceReport::point2);
}

void bindObjects(py::class_<Scene, std::shared_ptr<Scene>>& c) {
  c.def(
       "add_box",
       [](Scene& s, const std::string& id, const Eigen::Vector3d& size, const Eigen::Isometry3d& pose) {
         Shape shape = primitive(ShapeType::kBox);
         shape.box_size = size;
         addShape(s, id, shape, pose);
       },
       py::arg("id"), py::arg("size"), identityPose("pose"), "A box of full extents size (x, y, z) centred at pose.")
      .def(
          "add_sphere",
          [](Scene& s, const std::string& id, double radius, const Eigen::Isometry3d& pose) {
            Shape shape = primitive(ShapeType::kSphere);
            shape.radius = radius;
            addShape(s, id, shape, pose);
          },
          py::arg("id"), py::arg("radius"), identityPose("pose"))
      .def(
          "add_cylinder",
          [](Scene& s, const std::string& id, double radius, double length, const Eigen::Isometry3d& pose) {
            Shape shape = primitive(ShapeType::kCylinder);
            shape.radius = radius;
            shape.length = length;
            addShape(s, id, shape, pose);
          },
          py::arg("id"), py::arg("radius"), py::arg("length"), identityPose("pose"),
          "A cylinder along the pose's z axis.")
      .def(
          "add_mesh",
          [](Scene& s, const std::string& id, const std::string& path, const Eigen::Isometry3d& pose,
             const Eigen::Vector3d& scale) {
            Shape shape = primitive(ShapeType::kMesh);
            shape.mesh_resource = shape.mesh_path = path;
            shape.mesh_scale = scale;
            addShape(s, id, shape, pose);
          },
          py::arg("id"), py::arg("path"), identityPose("pose"), py::arg("scale") = Eigen::Vector3d::Ones(),
          "A mesh file (STL, OBJ, DAE).")
      .def("add_object", &addObject, py::arg("id"), py::arg("shapes"), identityPose("pose"),
           "An object of several PlacedShapes, placed in the object's frame.")
      .def(
          "move_object",
          [](Scene& s, const std::string& id, const Eigen::Isometry3d& pose) {
            check(s.edit().moveWorldObject(id, pose));
          },
          py::arg("id"), py::arg("pose"))
      .def(
          "remove_object", [](Scene& s, const std::string& id) { check(s.edit().removeWorldObject(id)); },
          py::arg("id"))
      .def(
          "clear", [](Scene& s) { s.edit().clearWorld(); }, "Removes every world object.")
      .def_property_readonly("world_object_ids", [](const Scene& s) { return s.read().worldObjectIds(); })
      .def(
          "has_world_object", [](const Scene& s, const std::string& id) { return s.read().hasWorldObject(id); },
          py::arg("id"))
      .def(
          "attach_object",
          [](Scene& s, const std::string& id, const std::string& link, std::vector<PlacedShape> shapes,
             const Eigen::Isometry3d& pose_in_link, const std::vector<std::string>& touch_links) {
            check(s.edit().attachObject(AttachedObject{id, link, pose_in_link, std::move(shapes), touch_links}));
            s.attached_links[id] = link;
          },
          py::arg("id"), py::arg("link"), py::arg("shapes"), identityPose("pose_in_link"),
          py::arg("touch_links") = std::vector<std::string>(),
          "A new object held by a link; it may touch the link and the touch_links.")
      .def(
          "attach_world_object",
          [](Scene& s, const std::string& id, const std::string& link, const RobotState& state,
             const std::vector<std::string>& touch_links) {
            s.checkState(state, "state");
            check(s.edit().attachWorldObject(id, link, state.linkTransform(link), touch_links));
            s.attached_links[id] = link;
          },
          py::arg("id"), py::arg("link"), py::arg("state"), py::arg("touch_links") = std::vector<std::string>(),
          "Attaches a world object where it is, to the link as posed in state.")
      .def(
          "detach_object",
          [](Scene& s, const std::string& id, const RobotState& state) {
            s.checkState(state, "state");
            const auto link = s.attached_links.find(id);
            if (link == s.attached_links.end())
              throw std::invalid_argument("detach: unknown attached object '" + id + "'");
            check(s.edit().detachObject(id, state.linkTransform(link->second)));
            s.attached_links.erase(link);
          },
          py::arg("id"), py::arg("state"), "Puts an attached object back into the world where state holds it.")
      .def(
          "remove_attached_object",
          [](Scene& s, const std::string& id) {
            check(s.edit().removeAttachedObject(id));
            s.attached_links.erase(id);
          },
          py::arg("id"))
      .def_property_readonly("attached_object_ids", [](const Scene& s) { return s.read().attachedObjectIds(); })
      .def(
          "has_attached_object", [](const Scene& s, const std::string& id) { return s.read().hasAttachedObject(id); },
          py::arg("id"));
}

}  // namespace

Scene::Scene(ModelPtr model, const CollisionSceneOptions& options)
    : model_(std::move(model)),
      scene_(std::make_shared<CollisionScene>(model_->collisionGeometry(), disabledPairs(*model_), options)) {
  for (const std::string& link : scene_->linkNames()) link_to_model_.push_back(model_->linkIndex(link));
}

Scene::Scene(const Scene& other)
    : attached_links(other.attached_links),
      model_(other.model_),
      scene_(std::make_shared<CollisionScene>(*other.scene_)),
      link_to_model_(other.link_to_model_) {}

CollisionScene& Scene::edit() {
  if (*users_ > 0) throw std::runtime_error("the collision scene cannot change while a plan runs in it");
  return *scene_;
}

void Scene::checkState(const RobotState& state, const char* what) const {
  const RobotModel& model = state.model();
  if (&model == model_.get()) return;
  if (linkNames(model) != linkNames(*model_) || model.variableNames() != model_->variableNames()) {
    throw std::invalid_argument(std::string(what) + " is a state of robot '" + model.name() +
                                "' with other links or joints than the scene's robot '" + model_->name() + "'");
  }
}

std::vector<Eigen::Isometry3d> Scene::linkPoses(const RobotState& state) const {
  checkState(state, "state");
  std::vector<Eigen::Isometry3d> poses(link_to_model_.size());
  for (size_t i = 0; i < link_to_model_.size(); ++i) poses[i] = state.linkTransform(link_to_model_[i]);
  return poses;
}

// set_<name> (every robot link), set_link_<name> and link_<name>: one per-link property of the scene's robot.
void bindLinkProperty(py::class_<Scene, std::shared_ptr<Scene>>& scene, const std::string& name,
                      const char* every_link_doc, SceneStatus (CollisionScene::*set_every)(double),
                      SceneStatus (CollisionScene::*set_link)(const std::string&, double),
                      double (CollisionScene::*get)(const std::string&) const) {
  scene
      .def(("set_" + name).c_str(), [set_every](Scene& s, double value) { check((s.edit().*set_every)(value)); },
           py::arg(name.c_str()), every_link_doc)
      .def(("set_link_" + name).c_str(),
           [set_link](Scene& s, const std::string& link, double value) { check((s.edit().*set_link)(link, value)); },
           py::arg("link"), py::arg(name.c_str()))
      .def(("link_" + name).c_str(), [get](const Scene& s, const std::string& link) { return (s.read().*get)(link); },
           py::arg("link"), "NaN for an unknown link.");
}

void bindCollision(py::module_& m) {
  bindQueryTypes(m);
  py::class_<Scene, std::shared_ptr<Scene>> scene(
      m, "CollisionScene",
      "Collision checking (FCL) of a robot's states against itself and world objects, as move_group's scene: the "
      "model's collision geometry, with its SRDF's disabled pairs allowed. Changes a scene refuses raise SceneError; "
      "changing a scene while a plan runs in it raises RuntimeError.");
  scene
      .def(py::init([](const ModelPtr& model, double padding, double scale) {
             CollisionSceneOptions options;
             options.link_padding = padding;
             options.link_scale = scale;
             return std::make_shared<Scene>(model, options);
           }),
           py::arg("model"), py::arg("padding") = 0.0, py::arg("scale") = 1.0,
           "Robot links are scaled about their shapes' origins, then grown by padding (m).")
      .def_property_readonly("model", &Scene::model)
      .def_property_readonly(
          "link_names", [](const Scene& s) { return s.read().linkNames(); },
          "The links with collision geometry, in model order.")
      .def(
          "copy", [](const Scene& s) { return std::make_shared<Scene>(s); }, "An independent copy.");
  bindObjects(scene);
  scene
      .def(
          "set_allowed",
          [](Scene& s, const std::string& a, const std::string& b, bool allowed) {
            check(s.edit().setAllowed(a, b, allowed));
          },
          py::arg("a"), py::arg("b"), py::arg("allowed") = true, "Allows (or forbids) contact of two bodies.")
      .def(
          "set_default_allowed",
          [](Scene& s, const std::string& name, bool allowed) { check(s.edit().setDefaultAllowed(name, allowed)); },
          py::arg("name"), py::arg("allowed") = true, "Allows (or forbids) contact of a body with any other.")
      .def(
          "is_allowed",
          [](const Scene& s, const std::string& a, const std::string& b) {
            return s.read().allowedCollisionMatrix().isAllowed(a, b);
          },
          py::arg("a"), py::arg("b"));
  bindLinkProperty(scene, "padding", "Every robot link's padding (m, >= 0).", &CollisionScene::setPadding,
                   &CollisionScene::setLinkPadding, &CollisionScene::linkPadding);
  bindLinkProperty(scene, "scale", "Every robot link's scale (> 0).", &CollisionScene::setScale,
                   &CollisionScene::setLinkScale, &CollisionScene::linkScale);
  scene
      .def(
          "is_colliding",
          [](const Scene& s, const RobotState& state, CollisionScope scope) {
            return s.read().isColliding(s.linkPoses(state), scope);
          },
          py::arg("state"), py::arg("scope") = CollisionScope::kAll)
      .def(
          "check_collision",
          [](const Scene& s, const RobotState& state, CollisionScope scope, std::size_t max_contacts_per_pair,
             std::size_t max_pairs) {
            return s.read().checkCollision(s.linkPoses(state),
                                           CollisionRequest{scope, max_contacts_per_pair, max_pairs});
          },
          py::arg("state"), py::arg("scope") = CollisionScope::kAll, py::arg("max_contacts_per_pair") = 1,
          py::arg("max_pairs") = 0, "Contacts of every colliding pair (max_pairs 0: every pair).")
      .def(
          "distance",
          [](const Scene& s, const RobotState& state, CollisionScope scope) {
            return s.read().distance(s.linkPoses(state), scope);
          },
          py::arg("state"), py::arg("scope") = CollisionScope::kAll)
      .def("set_to_random_valid_positions", &setToRandomValidPositions, py::arg("state"), py::arg("sampler"),
           py::arg("group") = py::none(), py::arg("max_attempts") = 1000,
           "Draws states from the sampler (every variable, or the group's) until one is within bounds and "
           "collision-free, and sets it; False (state unchanged) when none was within max_attempts.");
}

}  // namespace sixdof_core::python
