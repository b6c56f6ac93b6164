// The suction cup: its configuration (grasping.yaml `suction:`, the URDF's sixdof_suction block) and the World's
// seal test, attach and release (the rules are in sixdof_sim/suction.h).
#include "sixdof_sim/suction.h"

#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <stdexcept>

#include "gazebo_extensions.h"
#include "sixdof_sim/grasp_fix.h"
#include "world_impl.h"

namespace sixdof_sim {
namespace {

constexpr double kMaxContactDistance = 0.02;  // m

double parseNumber(const std::string& text, const std::string& where) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(where + " must be a number, got '" + text + "'");
  }
  return value;
}

// Sets one key of a suction configuration from its text (YAML scalar or XML element text).
void setField(SuctionConfig* config, const std::string& key, const std::string& text, const std::string& where) {
  if (key == "arm_name") {
    config->arm_name = text;
  } else if (key == "cup_link") {
    config->cup_link = text;
  } else if (key == "controller") {
    config->controller = text;
  } else if (key == "max_payload") {
    config->max_payload = parseNumber(text, where);
  } else if (key == "tilt_tolerance") {
    config->tilt_tolerance = parseNumber(text, where);
  } else if (key == "contact_distance") {
    config->contact_distance = parseNumber(text, where);
  } else {
    throw std::invalid_argument(where +
                                ": unknown key (arm_name, cup_link, max_payload, tilt_tolerance, "
                                "contact_distance, controller)");
  }
}

// Only dynamic objects are held; the robot's own links are not seen by the ray.
struct ObjectRay : btCollisionWorld::ClosestRayResultCallback {
  using btCollisionWorld::ClosestRayResultCallback::ClosestRayResultCallback;
  bool needsCollision(btBroadphaseProxy* proxy) const override {
    const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
    return object->getUserIndex() == kObjectBody && !object->isStaticObject() &&
           btCollisionWorld::ClosestRayResultCallback::needsCollision(proxy);
  }
};

}  // namespace

void validateSuctionConfig(const SuctionConfig& config) {
  if (config.cup_link.empty()) throw std::invalid_argument("suction: 'cup_link' is required");
  if (config.controller.empty()) throw std::invalid_argument("suction: 'controller' must not be empty");
  if (!(config.max_payload > 0.0) || !std::isfinite(config.max_payload)) {
    throw std::invalid_argument("suction: 'max_payload' must be > 0 (kg)");
  }
  if (!(config.tilt_tolerance > 0.0 && config.tilt_tolerance <= M_PI / 2.0)) {
    throw std::invalid_argument("suction: 'tilt_tolerance' must be in (0, pi/2] (rad)");
  }
  if (!(config.contact_distance > 0.0 && config.contact_distance <= kMaxContactDistance)) {
    throw std::invalid_argument("suction: 'contact_distance' must be in (0, 0.02] (m)");
  }
}

std::optional<SuctionConfig> parseSuctionYaml(const std::string& yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(source + ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["suction"]) return std::nullopt;
  const YAML::Node suction = root["suction"];
  if (!suction.IsMap()) throw std::invalid_argument(source + ": 'suction' must be a mapping");
  SuctionConfig config;
  for (const auto& entry : suction) {
    const std::string key = entry.first.as<std::string>();
    const std::string where = source + ": 'suction." + key + "'";
    if (!entry.second.IsScalar()) throw std::invalid_argument(where + " has a value of the wrong type");
    setField(&config, key, entry.second.Scalar(), where);
  }
  try {
    validateSuctionConfig(config);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
  return config;
}

std::optional<SuctionConfig> parseSuctionPlugin(const std::string& urdf_xml) {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* plugin = findGazeboPlugin(parseUrdfRobot(doc, urdf_xml), "sixdof_suction");
  if (plugin == nullptr) return std::nullopt;
  SuctionConfig config;
  for (const auto* e = plugin->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string where = std::string("sixdof_suction: <") + e->Name() + ">";
    std::string text = e->GetText() != nullptr ? e->GetText() : "";
    const auto begin = text.find_first_not_of(" \t\r\n");
    text = begin == std::string::npos ? "" : text.substr(begin, text.find_last_not_of(" \t\r\n") - begin + 1);
    setField(&config, e->Name(), text, where);
  }
  validateSuctionConfig(config);
  return config;
}

GraspingConfig parseGraspingConfig(const std::string& yaml_text, const std::string& source) {
  GraspingConfig out;
  out.suction = parseSuctionYaml(yaml_text, source);
  const YAML::Node root = YAML::Load(yaml_text);  // readable: parseSuctionYaml has loaded it
  if (root.IsMap() && root["grasp_fix"]) out.grasp_fix = parseGraspingYaml(yaml_text, source);
  if (!out.grasp_fix && !out.suction) throw std::invalid_argument(source + ": no 'grasp_fix' or 'suction' mapping");
  return out;
}

void World::Impl::configureSuction(const std::string& urdf_xml) {
  try {
    const std::optional<SuctionConfig> own = parseSuctionPlugin(urdf_xml);
    suction_config = own ? own : options.suction_config;
    if (suction_config) validateSuctionConfig(*suction_config);
  } catch (const std::invalid_argument& e) {
    throw WorldError(e.what());
  }
  if (suction_config && !links.count(suction_config->cup_link)) {
    throw WorldError("suction: cup_link '" + suction_config->cup_link + "' is not a URDF link");
  }
}

void World::Impl::pushSuctionEvent(GraspEvent::Type type) {
  GraspEvent event;
  event.type = type;
  event.sim_time = static_cast<double>(steps) * dt();
  event.arm = suction_config->arm_name;
  event.object = suction.held;
  event.palm_link = suction_config->cup_link;
  event.gripper_links = {suction_config->cup_link};
  grasp_events.push_back(event);
}

void World::Impl::stepSuction() {
  if (!suction.vacuum || !suction.held.empty()) return;
  const SuctionConfig& config = *suction_config;
  Eigen::Isometry3d cup;
  linkWorldPose(config.cup_link, &cup);
  const Eigen::Vector3d axis = cup.linear().col(2);
  const btVector3 from = toBt(cup.translation() - config.contact_distance * axis);
  const btVector3 to = toBt(cup.translation() + config.contact_distance * axis);
  ObjectRay ray(from, to);
  world->rayTest(from, to, ray);
  suction.refused.clear();
  if (!ray.hasHit()) return;
  const double tilt = std::acos(std::max(-1.0, std::min(1.0, -toEigen(ray.m_hitNormalWorld).normalized().dot(axis))));
  if (tilt > config.tilt_tolerance) return;
  auto* object = static_cast<ObjectRuntime*>(ray.m_collisionObject->getUserPointer());
  if (object->spec.mass > config.max_payload) {
    suction.refused = object->spec.name;
    return;
  }
  const int body = links.at(config.cup_link).body;
  const btTransform body_to_object = bodyWorld(body).inverse() * object->body->getWorldTransform();
  suction.constraint = std::make_unique<btMultiBodyFixedConstraint>(
      multibody.get(), bodies[body].bullet_link, object->body.get(), body_to_object.getOrigin(), btVector3(0, 0, 0),
      body_to_object.getBasis(), btMatrix3x3::getIdentity());
  suction.constraint->setMaxAppliedImpulse(kGraspConstraintMaxImpulse);
  suction.constraint->finalizeMultiDof();
  world->addMultiBodyConstraint(suction.constraint.get());
  setCupContacts(object, false);
  object->body->activate(true);
  suction.held = object->spec.name;
  setArticulatedWarmstarting(false);
  pushSuctionEvent(GraspEvent::Type::kAttached);
}

// A held object is fixed to the cup's body, touching the cup's face: their contacts would push it off the pose the
// constraint holds, and the solver's fight between the two turns the wrist (on the sixdof arm, joint6 off its goal by
// over 10 mrad with a cube in the air). So the pair does not collide while held, and collides again once let go.
void World::Impl::setCupContacts(ObjectRuntime* object, bool on) {
  const int link = bodies[links.at(suction_config->cup_link).body].bullet_link;
  btCollisionObject* cup = link < 0 ? multibody->getBaseCollider() : multibody->getLink(link).m_collider;
  if (cup == nullptr) return;
  object->body->setIgnoreCollisionCheck(cup, !on);
  if (on || object->body->getBroadphaseHandle() == nullptr || cup->getBroadphaseHandle() == nullptr) return;
  // The pair stays in the broadphase (so that it collides again as soon as the object is let go) but its contact
  // points go: a pair that is not checked keeps its manifold, and the solver would go on using its last points.
  btBroadphasePair* pair = world->getBroadphase()->getOverlappingPairCache()->findPair(
      object->body->getBroadphaseHandle(), cup->getBroadphaseHandle());
  if (pair == nullptr || pair->m_algorithm == nullptr) return;
  btManifoldArray manifolds;
  pair->m_algorithm->getAllContactManifolds(manifolds);
  for (int i = 0; i < manifolds.size(); ++i) manifolds[i]->clearManifold();
}

void World::Impl::releaseSuction() {
  if (!suction.constraint) return;
  world->removeMultiBodyConstraint(suction.constraint.get());
  suction.constraint.reset();
  if (ObjectRuntime* object = findObject(suction.held)) setCupContacts(object, true);
  setArticulatedWarmstarting(true);
  pushSuctionEvent(GraspEvent::Type::kDetached);
  suction.held.clear();
}

bool World::suctionAvailable() const { return impl_->suction_config.has_value(); }
const std::optional<SuctionConfig>& World::suctionConfig() const { return impl_->suction_config; }
bool World::vacuum() const { return impl_->suction.vacuum; }
std::string World::suctionHeld() const { return impl_->suction.held; }
std::string World::suctionRefused() const { return impl_->suction.refused; }

Result World::setVacuum(bool on) {
  Impl& d = *impl_;
  if (!d.suction_config) {
    return {Status::kInvalidArgument, "no suction configuration (URDF sixdof_suction block or grasping.yaml)"};
  }
  d.suction.vacuum = on;
  if (!on) {
    d.releaseSuction();
    d.suction.refused.clear();
  }
  return Result::success();
}

}  // namespace sixdof_sim
