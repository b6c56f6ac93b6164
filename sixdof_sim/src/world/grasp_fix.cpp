#include "sixdof_sim/grasp_fix.h"

#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "gazebo_extensions.h"

namespace sixdof_sim {
namespace {

constexpr double kMinForce = 1e-4;         // N: shorter forces are not considered (original semantics)
constexpr double kMinForceLengthRatio = 0.3;  // shorter/longer force of a gripping pair

std::string elementText(const tinyxml2::XMLElement* element, const std::string& name) {
  const char* text = element->GetText();
  if (text == nullptr) throw std::invalid_argument("gazebo_grasp_fix: <" + name + "> is empty");
  std::string value(text);
  const auto begin = value.find_first_not_of(" \t\r\n");
  const auto end = value.find_last_not_of(" \t\r\n");
  if (begin == std::string::npos) throw std::invalid_argument("gazebo_grasp_fix: <" + name + "> is empty");
  return value.substr(begin, end - begin + 1);
}

// The element `name` among the children of `plugin` or of its <arm>; nullptr if absent.
const tinyxml2::XMLElement* findParameter(const tinyxml2::XMLElement* plugin, const tinyxml2::XMLElement* arm,
                                          const char* name) {
  const tinyxml2::XMLElement* element = plugin->FirstChildElement(name);
  if (element == nullptr && arm != nullptr) element = arm->FirstChildElement(name);
  return element;
}

double readDouble(const tinyxml2::XMLElement* element, const char* name) {
  double value = 0.0;
  if (element->QueryDoubleText(&value) != tinyxml2::XML_SUCCESS || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("gazebo_grasp_fix: <") + name + "> must be a number");
  }
  return value;
}

int readInt(const tinyxml2::XMLElement* element, const char* name) {
  int value = 0;
  if (element->QueryIntText(&value) != tinyxml2::XML_SUCCESS) {
    throw std::invalid_argument(std::string("gazebo_grasp_fix: <") + name + "> must be an integer");
  }
  return value;
}

// gazebo_grasp_fix's defaults for what a configuration leaves out (grip_count_threshold: max_grip_count / 2).
GraspFixConfig pluginDefaults() {
  GraspFixConfig config;
  config.forces_angle_tolerance = 120.0;
  config.update_rate = 5.0;
  config.max_grip_count = 10;
  config.grip_count_threshold = config.max_grip_count / 2;
  config.release_tolerance = 0.005;
  config.disable_collisions_on_attach = false;
  return config;
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = a.normalized().dot(b.normalized());
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

}  // namespace

void validateGraspFixConfig(const GraspFixConfig& config) {
  if (config.palm_link.empty()) throw std::invalid_argument("gazebo_grasp_fix: <palm_link> missing");
  if (config.gripper_links.empty()) throw std::invalid_argument("gazebo_grasp_fix: no <gripper_link>");
  if (!(config.forces_angle_tolerance >= 90.0 && config.forces_angle_tolerance <= 180.0)) {
    throw std::invalid_argument("gazebo_grasp_fix: <forces_angle_tolerance> must be in [90, 180] degrees");
  }
  if (!(config.update_rate > 0.0) || !std::isfinite(config.update_rate)) {
    throw std::invalid_argument("gazebo_grasp_fix: <update_rate> must be > 0");
  }
  if (config.grip_count_threshold < 0) {
    throw std::invalid_argument("gazebo_grasp_fix: <grip_count_threshold> must be >= 0");
  }
  if (config.max_grip_count <= config.grip_count_threshold) {
    // An object can only be attached once its count exceeds the threshold.
    throw std::invalid_argument("gazebo_grasp_fix: <max_grip_count> must be > <grip_count_threshold>");
  }
  if (!(config.release_tolerance > 0.0) || !std::isfinite(config.release_tolerance)) {
    throw std::invalid_argument("gazebo_grasp_fix: <release_tolerance> must be > 0");
  }
}

std::optional<GraspFixConfig> parseGraspFixConfig(const std::string& urdf_xml) {
  tinyxml2::XMLDocument doc;
  return readGraspFixPlugin(parseUrdfRobot(doc, urdf_xml));
}

std::optional<GraspFixConfig> readGraspFixPlugin(const tinyxml2::XMLElement& robot) {
  const tinyxml2::XMLElement* plugin = findGazeboPlugin(robot, "gazebo_grasp_fix");
  if (plugin == nullptr) return std::nullopt;

  // gazebo-pkgs' newer format puts arm_name/palm_link/gripper_link in <arm>, the older one directly in
  // <plugin>; the tuning parameters are plugin-level in both. Both are accepted.
  const tinyxml2::XMLElement* arm = plugin->FirstChildElement("arm");
  if (arm != nullptr && arm->NextSiblingElement("arm") != nullptr) {
    throw std::invalid_argument("gazebo_grasp_fix: several <arm> blocks; one gripper is supported");
  }
  const tinyxml2::XMLElement* links_parent = arm != nullptr ? arm : plugin;

  // Defaults of the original plugin where the block omits a value.
  GraspFixConfig config = pluginDefaults();

  if (const auto* e = links_parent->FirstChildElement("arm_name")) config.arm_name = elementText(e, "arm_name");
  const auto* palm = links_parent->FirstChildElement("palm_link");
  if (palm == nullptr) throw std::invalid_argument("gazebo_grasp_fix: <palm_link> missing");
  config.palm_link = elementText(palm, "palm_link");
  for (const auto* e = links_parent->FirstChildElement("gripper_link"); e != nullptr;
       e = e->NextSiblingElement("gripper_link")) {
    config.gripper_links.push_back(elementText(e, "gripper_link"));
  }
  if (const auto* e = findParameter(plugin, arm, "forces_angle_tolerance")) {
    config.forces_angle_tolerance = readDouble(e, "forces_angle_tolerance");
  }
  if (const auto* e = findParameter(plugin, arm, "update_rate")) config.update_rate = readDouble(e, "update_rate");
  if (const auto* e = findParameter(plugin, arm, "max_grip_count")) {
    config.max_grip_count = readInt(e, "max_grip_count");
  }
  config.grip_count_threshold = config.max_grip_count / 2;
  if (const auto* e = findParameter(plugin, arm, "grip_count_threshold")) {
    config.grip_count_threshold = readInt(e, "grip_count_threshold");
  }
  if (const auto* e = findParameter(plugin, arm, "release_tolerance")) {
    config.release_tolerance = readDouble(e, "release_tolerance");
  }
  if (const auto* e = findParameter(plugin, arm, "disable_collisions_on_attach")) {
    const std::string value = elementText(e, "disable_collisions_on_attach");
    if (value == "true" || value == "1") {
      config.disable_collisions_on_attach = true;
    } else if (value == "false" || value == "0") {
      config.disable_collisions_on_attach = false;
    } else {
      throw std::invalid_argument("gazebo_grasp_fix: <disable_collisions_on_attach> must be true or false");
    }
  }
  validateGraspFixConfig(config);
  return config;
}

GraspFixConfig parseGraspingYaml(const std::string& yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(source + ": not valid YAML: " + e.msg);
  }
  const YAML::Node fix = root.IsMap() ? root["grasp_fix"] : YAML::Node();
  if (!fix || !fix.IsMap()) throw std::invalid_argument(source + ": no 'grasp_fix' mapping");
  GraspFixConfig config = pluginDefaults();
  bool threshold_given = false;
  // Each key's reader (yaml-cpp's as<T>() throws on a value of the wrong type); `where` names the key.
  using Reader = std::function<void(const YAML::Node& value, const std::string& where)>;
  const auto read = [](auto* field) -> Reader {
    return [field](const YAML::Node& value, const std::string&) {
      *field = value.as<std::remove_pointer_t<decltype(field)>>();
    };
  };
  const std::map<std::string, Reader> readers = {
      {"arm_name", read(&config.arm_name)},
      {"palm_link", read(&config.palm_link)},
      {"gripper_links",
       [&config](const YAML::Node& value, const std::string& where) {
         if (!value.IsSequence()) throw std::invalid_argument(where + " must be a list of link names");
         config.gripper_links = value.as<std::vector<std::string>>();
       }},
      {"forces_angle_tolerance", read(&config.forces_angle_tolerance)},
      {"update_rate", read(&config.update_rate)},
      {"grip_count_threshold",
       [&](const YAML::Node& value, const std::string&) {
         config.grip_count_threshold = value.as<int>();
         threshold_given = true;
       }},
      {"max_grip_count", read(&config.max_grip_count)},
      {"release_tolerance", read(&config.release_tolerance)},
      {"disable_collisions_on_attach", read(&config.disable_collisions_on_attach)},
  };
  for (const auto& entry : fix) {
    const std::string key = entry.first.as<std::string>();
    const auto reader = readers.find(key);
    if (reader == readers.end()) throw std::invalid_argument(source + ": unknown key 'grasp_fix." + key + "'");
    const std::string where = source + ": 'grasp_fix." + key + "'";
    try {
      reader->second(entry.second, where);
    } catch (const YAML::Exception&) {
      throw std::invalid_argument(where + " has a value of the wrong type");
    }
  }
  if (!threshold_given) config.grip_count_threshold = config.max_grip_count / 2;
  try {
    validateGraspFixConfig(config);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
  return config;
}

GraspFix::GraspFix(const GraspFixConfig& config, PoseLookup link_pose, PoseLookup object_pose)
    : config_(config), link_pose_(std::move(link_pose)), object_pose_(std::move(object_pose)) {
  validateGraspFixConfig(config_);
  period_ = 1.0 / config_.update_rate;
  reset();
}

void GraspFix::reset() {
  next_update_ = period_;
  window_.clear();
  grip_counts_.clear();
  attached_.clear();
  attach_reference_.clear();
}

void GraspFix::forget(const std::string& object) {
  window_.erase(object);
  grip_counts_.erase(object);
  if (attached_ == object) {
    attached_.clear();
    attach_reference_.clear();
  }
}

int GraspFix::gripCount(const std::string& object) const {
  const auto it = grip_counts_.find(object);
  return it == grip_counts_.end() ? 0 : it->second;
}

bool GraspFix::isGripped(const LinkContacts& links) const {
  const double min_angle = config_.forces_angle_tolerance * M_PI / 180.0;
  std::vector<Eigen::Vector3d> forces;
  for (const auto& entry : links) forces.push_back(entry.second.force / entry.second.samples);
  for (size_t i = 0; i < forces.size(); ++i) {
    for (size_t j = i + 1; j < forces.size(); ++j) {
      const double l1 = forces[i].norm();
      const double l2 = forces[j].norm();
      if (l1 < kMinForce || l2 < kMinForce) continue;
      const double ratio = std::min(l1, l2) / std::max(l1, l2);
      if (angleBetween(forces[i], forces[j]) > min_angle && ratio >= kMinForceLengthRatio) {
        return true;
      }
    }
  }
  return false;
}

bool GraspFix::shouldRelease() const {
  Eigen::Isometry3d object_pose;
  if (!object_pose_(attached_, &object_pose)) return true;
  for (const auto& entry : attach_reference_) {
    Eigen::Isometry3d link_pose;
    if (!link_pose_(entry.first, &link_pose)) continue;
    const Accumulated& ref = entry.second;
    const Eigen::Vector3d point_in_link = ref.point_in_link / ref.samples;
    const Eigen::Vector3d object_in_link = ref.object_in_link / ref.samples;
    const double attach_distance = (point_in_link - object_in_link).norm();
    const double distance = (link_pose * point_in_link - object_pose.translation()).norm();
    if (std::abs(distance - attach_distance) > config_.release_tolerance) return true;
  }
  return false;
}

GraspDecision GraspFix::update(double sim_time, const std::vector<GraspContact>& contacts) {
  GraspDecision decision;
  for (const GraspContact& contact : contacts) {
    if (std::find(config_.gripper_links.begin(), config_.gripper_links.end(), contact.link) ==
        config_.gripper_links.end()) {
      continue;
    }
    Eigen::Isometry3d link_pose;
    Eigen::Isometry3d object_pose;
    if (!link_pose_(contact.link, &link_pose) || !object_pose_(contact.object, &object_pose)) continue;
    const Eigen::Isometry3d world_to_link = link_pose.inverse();
    Accumulated& acc = window_[contact.object][contact.link];
    acc.force += contact.force_on_object;
    acc.point_in_link += world_to_link * contact.point;
    acc.object_in_link += world_to_link * object_pose.translation();
    ++acc.samples;
  }

  // Prompt release (checked every step): the fingers moved away from the attach-time contact points.
  if (!attached_.empty() && shouldRelease()) {
    decision.detach.push_back(attached_);
    grip_counts_[attached_] = 0;
    attached_.clear();
    attach_reference_.clear();
  }

  // A nanosecond of slack: update instants are multiples of the period despite floating-point rounding.
  if (sim_time + 1e-9 < next_update_) return decision;
  while (next_update_ <= sim_time + 1e-9) next_update_ += period_;

  std::map<std::string, LinkContacts> window;
  window.swap(window_);
  std::vector<std::string> gripped;
  for (const auto& entry : window) {
    if (!isGripped(entry.second)) continue;
    gripped.push_back(entry.first);
    int& count = grip_counts_[entry.first];
    if (count < config_.max_grip_count) ++count;
    if (attached_.empty() && count > config_.grip_count_threshold) {
      attached_ = entry.first;
      attach_reference_ = entry.second;
      decision.attach.push_back(entry.first);
    }
  }
  for (auto it = grip_counts_.begin(); it != grip_counts_.end();) {
    if (std::find(gripped.begin(), gripped.end(), it->first) != gripped.end()) {
      ++it;
      continue;
    }
    if (it->second > 0) --it->second;
    // Original semantics: a decayed count triggers the geometric release check too (covered above
    // every step); counts of zero for objects not held are dropped to keep the map small.
    if (it->second == 0 && it->first != attached_) {
      it = grip_counts_.erase(it);
    } else {
      ++it;
    }
  }
  return decision;
}

}  // namespace sixdof_sim
