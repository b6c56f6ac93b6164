#include "sixdof_core/setup_assistant.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "sixdof_core/collision.h"
#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/ik_solver.h"
#include "sixdof_core/result.h"

// The collision matrix and its merge into an SRDF; describeModel() is in setup_assistant/describe_model.cpp,
// the command line of setup_assistant_core in setup_assistant/command_line.cpp.

namespace sixdof_core {

namespace {

using LinkPair = std::pair<int, int>;  // link indices, first < second

LinkPair orderedPair(int a, int b) { return a < b ? LinkPair(a, b) : LinkPair(b, a); }

bool isComputedReason(const std::string& reason) {
  return reason == "Adjacent" || reason == "Default" || reason == "Always" || reason == "Never" ||
         reason == "Gripper";
}

int reasonRank(const std::string& reason) {
  if (reason == "Adjacent") return 0;
  if (reason == "Default") return 1;
  if (reason == "Always") return 2;
  if (reason == "Never") return 3;
  if (reason == "Gripper") return 4;
  return 5;
}

// The robot name of a URDF, so that a model can be built without an SRDF ("" when unreadable: the
// URDF parser then reports the actual problem).
std::string urdfRobotName(const std::string& urdf_xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) return "";
  const char* name = doc.RootElement()->Attribute("name");
  return name ? name : "";
}

// The links of the model's grippers: every SRDF end effector's parent link and the links below it.
std::set<int> gripperLinks(const RobotModel& model) {
  std::set<int> found;
  for (const auto& eef : model.endEffectors()) found.insert(model.linkIndex(eef.parent_link));
  // Model order is topological: a link's parent comes before it.
  for (size_t l = 1; l < model.links().size(); ++l) {
    if (found.count(model.links()[l].parent_link)) found.insert(static_cast<int>(l));
  }
  return found;
}

std::string emptySrdf(const std::string& robot_name) {
  SrdfDocument document;
  document.robot_name = robot_name;
  return writeSrdf(document);
}

}  // namespace

std::string reasonName(DisableReason reason) {
  static constexpr const char* kNames[] = {"Adjacent", "Default", "Always", "Never", "Gripper"};
  return enumName<DisableReason::kGripper>(reason, kNames, "");
}

std::vector<std::pair<std::string, std::string>> adjacentLinkPairs(const RobotModel& model) {
  const auto& links = model.links();
  std::vector<std::vector<int>> neighbours(links.size());
  for (size_t l = 1; l < links.size(); ++l) {
    neighbours[l].push_back(links[l].parent_link);
    neighbours[links[l].parent_link].push_back(static_cast<int>(l));
  }
  auto has_geometry = [&](int l) { return !links[l].collision.shapes.empty(); };
  std::set<LinkPair> pairs;
  for (size_t start = 0; start < links.size(); ++start) {
    if (!has_geometry(start)) continue;
    // Walk through links without geometry: whatever link with geometry lies beyond them is adjacent.
    std::vector<int> stack{static_cast<int>(start)};
    std::set<int> seen{static_cast<int>(start)};
    while (!stack.empty()) {
      const int l = stack.back();
      stack.pop_back();
      for (int n : neighbours[l]) {
        if (!seen.insert(n).second) continue;
        if (has_geometry(n)) {
          pairs.insert(orderedPair(static_cast<int>(start), n));
        } else {
          stack.push_back(n);
        }
      }
    }
  }
  std::vector<std::pair<std::string, std::string>> result;
  for (const auto& [a, b] : pairs) result.emplace_back(links[a].name, links[b].name);
  return result;
}

std::vector<LinkGeometry> allLinkGeometry(const RobotModel& model) {
  std::vector<LinkGeometry> geometry;
  for (const auto& link : model.links()) geometry.push_back(link.collision);
  return geometry;
}

StateSampler::StateSampler(const RobotModel& model, std::uint64_t seed) : state_(seed) {
  for (size_t v = 0; v < model.variableCount(); ++v) {
    const auto& limits = model.variableJoint(v).limits;
    bounds_.emplace_back(limits.lower, limits.upper);
  }
}

Eigen::VectorXd StateSampler::sample() {
  Eigen::VectorXd q(bounds_.size());
  for (size_t v = 0; v < bounds_.size(); ++v) {
    // SplitMix64, then the top 53 bits as a double in [0, 1): fully specified, unlike the standard
    // library's distributions, so a seed gives the same SRDF with any compiler.
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    const double u = static_cast<double>(z >> 11) * 0x1.0p-53;
    q[v] = bounds_[v].first + u * (bounds_[v].second - bounds_[v].first);
  }
  return q;
}

DisabledCollisions computeDisabledCollisions(const RobotModelConstPtr& model,
                                                const CollisionMatrixOptions& options) {
  if (!model) throw std::invalid_argument("computeDisabledCollisions: no robot model");
  if (options.density == 0) throw std::invalid_argument("sampling density must be > 0");
  if (!(options.always_fraction > 0.0 && options.always_fraction < 1.0)) {
    throw std::invalid_argument("always_fraction must be in (0, 1)");
  }
  const auto& links = model->links();
  std::vector<int> with_geometry;
  for (size_t l = 0; l < links.size(); ++l) {
    if (!links[l].collision.shapes.empty()) with_geometry.push_back(static_cast<int>(l));
  }
  DisabledCollisions result;
  const size_t geometry_links = with_geometry.size();
  result.link_pairs = geometry_links < 2 ? 0 : geometry_links * (geometry_links - 1) / 2;

  std::map<LinkPair, ComputedPair> decided;
  auto decide = [&](int a, int b, DisableReason reason, size_t count) {
    const LinkPair p = orderedPair(a, b);
    decided[p] = ComputedPair{links[p.first].name, links[p.second].name, reason, count};
  };
  CollisionScene scene(allLinkGeometry(*model), {});
  for (const auto& [a, b] : adjacentLinkPairs(*model)) {
    decide(model->linkIndex(a), model->linkIndex(b), DisableReason::kAdjacent, 0);
    scene.setAllowed(a, b, true);
  }

  CollisionRequest request;
  request.scope = CollisionScope::kSelf;
  request.max_contacts_per_pair = 1;
  RobotState state(model);
  for (const auto& contact : scene.checkCollision(state.linkTransforms(), request).contacts) {
    decide(model->linkIndex(contact.body1), model->linkIndex(contact.body2), DisableReason::kDefault, 0);
    scene.setAllowed(contact.body1, contact.body2, true);
  }

  // Every pair still checked starts as a Never candidate. A pair that has collided and has also been
  // free in so many samples that it can no longer be Always is settled (enabled for good) and dropped
  // from the checks: most pairs settle early, which keeps high densities fast.
  std::map<LinkPair, size_t> collisions;
  std::set<LinkPair> undecided;
  for (size_t i = 0; i < with_geometry.size(); ++i) {
    for (size_t j = i + 1; j < with_geometry.size(); ++j) {
      const LinkPair p(with_geometry[i], with_geometry[j]);
      if (!decided.count(p)) undecided.insert(p);
    }
  }
  const double n = static_cast<double>(options.density);
  std::vector<LinkPair> settled;  // collided in some samples, free in enough others: checked when planning
  StateSampler sampler(*model, options.seed);
  const size_t progress_step = std::max<size_t>(1, options.density / 20);
  for (size_t s = 0; s < options.density && !undecided.empty(); ++s) {
    if (options.progress && s > 0 && s % progress_step == 0) options.progress(s, options.density);
    state.setPositions(sampler.sample());
    result.pair_checks += undecided.size();
    for (const auto& contact : scene.checkCollision(state.linkTransforms(), request).contacts) {
      ++collisions[orderedPair(model->linkIndex(contact.body1), model->linkIndex(contact.body2))];
    }
    const double done = static_cast<double>(s + 1);
    for (auto it = undecided.begin(); it != undecided.end();) {
      const size_t hits = collisions[*it];
      const double free = done - static_cast<double>(hits);
      if (hits > 0 && n - free <= options.always_fraction * n) {
        scene.setAllowed(links[it->first].name, links[it->second].name, true);
        settled.push_back(*it);
        it = undecided.erase(it);
      } else {
        ++it;
      }
    }
  }
  result.samples = options.density;
  if (options.progress) options.progress(options.density, options.density);
  for (const auto& p : undecided) {
    const size_t hits = collisions[p];
    if (hits == 0) {
      decide(p.first, p.second, DisableReason::kNever, 0);
    } else if (static_cast<double>(hits) > options.always_fraction * n) {
      decide(p.first, p.second, DisableReason::kAlways, hits);
    }
  }

  // Of the pairs left to be checked, those within a gripper: its joints alone move them relative to each other.
  const std::set<int> gripper = gripperLinks(*model);
  for (const auto& p : settled) {
    if (gripper.count(p.first) && gripper.count(p.second)) {
      decide(p.first, p.second, DisableReason::kGripper, collisions[p]);
    }
  }

  for (const auto& [p, pair] : decided) result.disabled.push_back(pair);
  std::stable_sort(result.disabled.begin(), result.disabled.end(), [](const auto& a, const auto& b) {
    return static_cast<int>(a.reason) < static_cast<int>(b.reason);
  });
  return result;
}

void addGroupsSkeleton(const RobotModel& model, SrdfDocument& document) {
  const auto& joints = model.joints();
  int last_revolute = -1;
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].type == JointType::kRevolute || joints[j].type == JointType::kContinuous) {
      last_revolute = static_cast<int>(j);
    }
  }
  if (last_revolute < 0) {
    throw std::invalid_argument("groups skeleton: robot '" + model.name() + "' has no revolute joint for an arm");
  }
  const std::string tip = joints[last_revolute].child_link;
  const auto chain = model.chainJoints(model.rootLink(), tip);
  const XmlElement chain_element{"chain", {{"base_link", model.rootLink()}, {"tip_link", tip}}, {}};
  document.groups.push_back(XmlElement{"group", {{"name", "arm"}}, {chain_element}});
  XmlElement gripper{"group", {{"name", "gripper"}}, {}};
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].type == JointType::kFixed) continue;
    if (std::find(chain.begin(), chain.end(), static_cast<int>(j)) != chain.end()) continue;
    gripper.children.push_back(XmlElement{"joint", {{"name", joints[j].name}}, {}});
  }
  if (gripper.children.empty()) return;
  document.groups.push_back(gripper);
  if (document.end_effectors.empty()) {
    document.end_effectors.push_back(
        XmlElement{"end_effector", {{"name", "hand"}, {"parent_link", tip}, {"group", "gripper"}}, {}});
  }
}

SetupAssistantOutput runSetupAssistant(const std::string& urdf_xml, const std::string& srdf_in_xml,
                                       const SetupAssistantOptions& options, const PackageResolver& resolver) {
  SrdfDocument document;
  std::string model_srdf;
  if (srdf_in_xml.empty()) {
    model_srdf = emptySrdf(urdfRobotName(urdf_xml));
    document.robot_name = urdfRobotName(urdf_xml);
  } else {
    document = parseSrdfDocument(srdf_in_xml);
    model_srdf = srdf_in_xml;
  }
  // The model validates the input SRDF against the URDF (names, limits, robot name).
  const auto model = std::make_shared<const RobotModel>(urdf_xml, model_srdf, resolver);

  SetupAssistantOutput result;
  if (options.groups_skeleton && document.groups.empty()) {
    addGroupsSkeleton(*model, document);
    result.skeleton_written = true;
  }
  result.collisions = computeDisabledCollisions(model, options.collision);

  std::vector<SrdfCollisionPair> manual;
  std::set<LinkPair> manual_pairs;
  for (const auto& pair : document.disabled_collisions) {
    if (isComputedReason(pair.reason)) continue;
    const LinkPair p = orderedPair(model->linkIndex(pair.link1), model->linkIndex(pair.link2));
    if (!manual_pairs.insert(p).second) continue;  // one entry per pair; the first one written wins
    manual.push_back(pair);
  }
  result.manual_pairs_kept = manual.size();
  std::vector<std::tuple<int, std::string, LinkPair, SrdfCollisionPair>> entries;
  for (const auto& pair : result.collisions.disabled) {
    const LinkPair p(model->linkIndex(pair.link1), model->linkIndex(pair.link2));
    if (manual_pairs.count(p)) continue;
    const std::string reason = reasonName(pair.reason);
    entries.emplace_back(reasonRank(reason), reason, p, SrdfCollisionPair{pair.link1, pair.link2, reason});
  }
  for (const auto& pair : manual) {
    const LinkPair p = orderedPair(model->linkIndex(pair.link1), model->linkIndex(pair.link2));
    entries.emplace_back(reasonRank(pair.reason), pair.reason, p, pair);
  }
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return std::tie(std::get<0>(a), std::get<1>(a), std::get<2>(a)) <
           std::tie(std::get<0>(b), std::get<1>(b), std::get<2>(b));
  });
  document.disabled_collisions.clear();
  for (const auto& entry : entries) document.disabled_collisions.push_back(std::get<3>(entry));

  result.srdf = writeSrdf(document);
  // What we write must load: this catches a skeleton that does not fit the model.
  RobotModel check(urdf_xml, result.srdf, resolver);
  return result;
}

SetupAssistantOutput runSetupAssistantOnFiles(const SetupAssistantCommand& command) {
  namespace fs = std::filesystem;
  // The folders above the URDF come first: a URDF usually lives in <package>/urdf/ and names its own
  // package's meshes, which an installed copy elsewhere on ROS_PACKAGE_PATH may lack.
  std::vector<std::string> roots;
  for (fs::path dir = fs::absolute(command.urdf_path).parent_path(); roots.size() < 3 && dir.has_relative_path();
       dir = dir.parent_path()) {
    roots.push_back(dir.string());
  }
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream in(env);
    for (std::string root; std::getline(in, root, ':');) {
      if (!root.empty()) roots.push_back(root);
    }
  }
  const std::string urdf = readTextFile(command.urdf_path);
  std::string srdf_in;
  if (!command.srdf_in_path.empty()) {
    srdf_in = readTextFile(command.srdf_in_path);
    if (srdf_in.empty()) throw RobotModelError("SRDF file '" + command.srdf_in_path + "' is empty");
  }
  const auto resolver = PackageResolver::fromSearchRoots(roots);
  auto write = [](const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out || !(out << text) || !out.flush()) throw RobotModelError("cannot write file '" + path + "'");
  };
  SetupAssistantOutput result;
  if (!command.urdf_out_path.empty()) {
    RepairResult repaired;
    try {
      repaired = repairModel(urdf, command.repair, resolver);
    } catch (const RobotModelError& e) {
      throw RobotModelError(std::string(e.what()) + " (URDF '" + command.urdf_path + "')");
    }
    write(command.urdf_out_path, repaired.urdf);
    write(command.repairs_path, describeRepairs(repaired));
    return result;
  }
  std::string description;
  try {
    if (command.srdf_out_path.empty()) {
      const std::string srdf = srdf_in.empty() ? emptySrdf(urdfRobotName(urdf)) : srdf_in;
      description = describeModel(RobotModel(urdf, srdf, resolver));
    } else {
      result = runSetupAssistant(urdf, srdf_in, command.options, resolver);
      if (!command.describe_path.empty()) {
        description = describeModel(RobotModel(urdf, result.srdf, resolver), &result.collisions);
      }
    }
  } catch (const RobotModelError& e) {
    throw RobotModelError(std::string(e.what()) + " (URDF '" + command.urdf_path + "'" +
                          (command.srdf_in_path.empty() ? "" : ", SRDF '" + command.srdf_in_path + "'") + ")");
  } catch (const SrdfError& e) {
    throw SrdfError(std::string(e.what()) + " (SRDF '" + command.srdf_in_path + "')");
  }
  if (!command.srdf_out_path.empty()) write(command.srdf_out_path, result.srdf);
  if (!command.describe_path.empty()) write(command.describe_path, description);
  return result;
}

}  // namespace sixdof_core
