// setup_assistant: computes an SRDF's disabled collision pairs (MoveIt Setup Assistant semantics) and writes
// the SRDF, keeping the hand-written parts of an existing one. Run `setup_assistant --help`.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sixdof_core/setup_assistant.h"

namespace {

namespace fs = std::filesystem;

const char* const kUsage =
    "usage: setup_assistant --urdf FILE [--srdf-in FILE] --srdf-out FILE [--density N] [--seed S]\n"
    "                       [--groups-skeleton]\n"
    "  --urdf FILE         robot description (package:// meshes are found via ROS_PACKAGE_PATH and\n"
    "                      the folders above the URDF)\n"
    "  --srdf-in FILE      existing SRDF: groups, states, end effectors, virtual/passive joints and\n"
    "                      disable_collisions entries with other reasons than Adjacent/Default/Always/Never\n"
    "                      are kept\n"
    "  --srdf-out FILE     where to write the SRDF (may be the same file as --srdf-in)\n"
    "  --density N         random samples for Always/Never (1000 low .. 100000 high; default 10000)\n"
    "  --seed S            random seed (default 0); the same inputs and seed give the same file\n"
    "  --groups-skeleton   when the input has no groups: arm = chain root -> last revolute joint's child,\n"
    "                      gripper = the other movable joints, end effector 'hand'\n";

int fail(const std::string& message) {
  std::cerr << "setup_assistant: " << message << "\n";
  return 2;
}

bool parseUnsigned(const std::string& text, unsigned long long& value) {
  if (text.empty() || text[0] == '-' || text[0] == '+') return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoull(text.c_str(), &end, 10);
  return errno == 0 && end && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> values;
  bool skeleton = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--groups-skeleton") {
      skeleton = true;
    } else if (arg == "--urdf" || arg == "--srdf-in" || arg == "--srdf-out" || arg == "--density" || arg == "--seed") {
      if (i + 1 >= argc) return fail(arg + " needs a value\n" + kUsage);
      values[arg] = argv[++i];
    } else {
      return fail("unknown argument '" + arg + "'\n" + kUsage);
    }
  }
  if (!values.count("--urdf")) return fail(std::string("--urdf is required\n") + kUsage);
  if (!values.count("--srdf-out")) return fail(std::string("--srdf-out is required\n") + kUsage);

  sixdof_core::SetupAssistantOptions options;
  options.groups_skeleton = skeleton;
  if (values.count("--density")) {
    unsigned long long density = 0;
    if (!parseUnsigned(values["--density"], density) || density == 0) {
      return fail("--density must be a whole number > 0, got '" + values["--density"] + "'");
    }
    options.collision.density = density;
  }
  if (values.count("--seed")) {
    unsigned long long seed = 0;
    if (!parseUnsigned(values["--seed"], seed)) {
      return fail("--seed must be a whole number >= 0, got '" + values["--seed"] + "'");
    }
    options.collision.seed = seed;
  }

  const std::string urdf_path = values["--urdf"];
  // The folders above the URDF come first (a URDF usually lives in <package>/urdf/ and names its own
  // package's meshes, which an installed copy elsewhere on ROS_PACKAGE_PATH may lack), then ROS_PACKAGE_PATH.
  std::vector<std::string> roots;
  for (fs::path dir = fs::absolute(urdf_path).parent_path(); roots.size() < 3 && dir.has_relative_path();
       dir = dir.parent_path()) {
    roots.push_back(dir.string());
  }
  if (const char* env = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream in(env);
    for (std::string root; std::getline(in, root, ':');) {
      if (!root.empty()) roots.push_back(root);
    }
  }

  try {
    const std::string urdf = sixdof_core::readTextFile(urdf_path);
    const std::string srdf_in = values.count("--srdf-in") ? sixdof_core::readTextFile(values["--srdf-in"]) : "";
    if (values.count("--srdf-in") && srdf_in.empty()) return fail("SRDF '" + values["--srdf-in"] + "' is empty");
    const auto start = std::chrono::steady_clock::now();
    const auto result = sixdof_core::runSetupAssistant(urdf, srdf_in, options,
                                                       sixdof_core::PackageResolver::fromSearchRoots(roots));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::ofstream out(values["--srdf-out"], std::ios::binary);
    if (!out || !(out << result.srdf) || !out.flush()) {
      return fail("cannot write '" + values["--srdf-out"] + "'");
    }
    std::map<std::string, int> counts;
    for (const auto& pair : result.collisions.disabled) ++counts[sixdof_core::reasonName(pair.reason)];
    std::cout << "link pairs with geometry: " << result.collisions.link_pairs << "\n";
    for (const char* reason : {"Adjacent", "Default", "Always", "Never"}) {
      std::cout << "  " << reason << ": " << counts[reason] << "\n";
    }
    std::cout << "  enabled (checked when planning): "
              << result.collisions.link_pairs - result.collisions.disabled.size() << "\n";
    if (result.manual_pairs_kept > 0) std::cout << "  kept hand-written entries: " << result.manual_pairs_kept << "\n";
    if (skeleton && !result.skeleton_written) std::cout << "groups skeleton not written: the input SRDF has groups\n";
    if (result.skeleton_written) std::cout << "groups skeleton written (arm, gripper, end effector hand)\n";
    std::cout << "samples: " << result.collisions.samples << " (seed " << options.collision.seed
              << "), pairwise checks: " << result.collisions.pair_checks << ", time: " << seconds << " s\n";
    std::cout << "wrote " << values["--srdf-out"] << "\n";
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}
