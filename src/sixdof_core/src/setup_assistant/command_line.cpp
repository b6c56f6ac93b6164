// The command line of `rosrun sixdof_core setup_assistant_core` (the C++ half of `setup_assistant`).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/setup_assistant.h"

namespace sixdof_core {

const char* const kSetupAssistantUsage =
    "usage: setup_assistant_core --urdf FILE [--srdf-in FILE] (--srdf-out FILE | --describe FILE)\n"
    "                            [--describe FILE] [--density N] [--seed S] [--groups-skeleton]\n"
    "       setup_assistant_core --urdf FILE --urdf-out FILE --repairs FILE [--inertia-density D]\n"
    "                            [--gripper-parent LINK --gripper-joint J ... [--pad-link L --pad-link L]\n"
    "                             [--closing-direction \"X Y Z\"] [--open J=V ...] [--closed J=V ...]\n"
    "                             [--tcp \"X Y Z ROLL PITCH YAW\" [--tcp-parent LINK]]]\n"
    "  The C++ half of `setup_assistant` (the command users run; it also expands xacro and generates\n"
    "  config packages). The URDF must be expanded (no xacro).\n"
    "  --urdf FILE         robot description (package:// meshes are found in the folders above the URDF,\n"
    "                      then via ROS_PACKAGE_PATH)\n"
    "  --srdf-in FILE      existing SRDF: groups, states, end effectors, virtual/passive joints and\n"
    "                      disable_collisions entries with other reasons than Adjacent/Default/Always/Never/\n"
    "                      Gripper\n"
    "                      are kept\n"
    "  --srdf-out FILE     where to write the SRDF (may be the same file as --srdf-in)\n"
    "  --describe FILE     write the model (links, joints, limits, groups with the IK solver that fits,\n"
    "                      states, end effectors, collision counts) as YAML; without --srdf-out: of the\n"
    "                      URDF (+ --srdf-in) model, without sampling\n"
    "  --density N         random samples for Always/Never/Gripper (1000 low .. 100000 high; default 10000)\n"
    "  --seed S            random seed (default 0); the same inputs and seed give the same file\n"
    "  --groups-skeleton   when the input has no groups: arm = chain root -> last revolute joint's child,\n"
    "                      gripper = the other movable joints, end effector 'hand'\n"
    "  Repair mode: --urdf-out FILE gets the URDF with an inertia computed for every moving link whose\n"
    "  <inertial> is missing or unusable (from its collision geometry, else its visual geometry, at\n"
    "  --inertia-density kg/m^3, default 1000; a default mass without geometry) and, with a gripper, its\n"
    "  TCP as a link 'tcp' unless one exists; --repairs FILE gets what was computed as YAML, with the\n"
    "  gripper's pads, open/closed positions, widths and TCP. The gripper options: its parent link (the\n"
    "  arm's tip), its joints, and values that replace the inferred ones (positions J=V, the TCP in the\n"
    "  frame of --tcp-parent, default the parent link; rpy in radians about fixed axes).\n";

namespace {

std::vector<double> parseNumbers(const std::string& option, const std::string& text, size_t count) {
  std::vector<double> values;
  const char* at = text.c_str();
  while (true) {
    while (*at == ' ' || *at == ',') ++at;
    if (*at == '\0') break;
    char* end = nullptr;
    const double value = std::strtod(at, &end);
    if (end == at || !std::isfinite(value)) break;
    values.push_back(value);
    at = end;
  }
  if (*at != '\0' || values.size() != count) {
    throw std::invalid_argument(option + " needs " + std::to_string(count) + " numbers, got '" + text + "'");
  }
  return values;
}

// "joint=value" (split at the last '=').
std::pair<std::string, double> parsePosition(const std::string& option, const std::string& text) {
  const size_t eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0) {
    throw std::invalid_argument(option + " needs JOINT=VALUE, got '" + text + "'");
  }
  return {text.substr(0, eq), parseNumbers(option, text.substr(eq + 1), 1)[0]};
}

bool parseWholeNumber(const std::string& text, unsigned long long& value) {
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoull(text.c_str(), &end, 10);
  return errno == 0 && *end == '\0';
}

}  // namespace

SetupAssistantCommand parseSetupAssistantArguments(const std::vector<std::string>& args) {
  SetupAssistantCommand command;
  std::map<std::string, std::string> values;
  GripperQuery gripper;
  bool gripper_given = false;
  const std::vector<std::string> single = {"--urdf", "--srdf-in", "--srdf-out", "--density", "--seed", "--describe",
                                           "--urdf-out", "--repairs", "--inertia-density", "--gripper-parent",
                                           "--closing-direction", "--tcp", "--tcp-parent"};
  const std::vector<std::string> gripper_options = {"--gripper-joint", "--pad-link", "--open", "--closed"};
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h") {
      command.help = true;
      return command;
    }
    if (arg == "--groups-skeleton") {
      command.options.groups_skeleton = true;
      continue;
    }
    const bool repeated = std::find(gripper_options.begin(), gripper_options.end(), arg) != gripper_options.end();
    if (!repeated && std::find(single.begin(), single.end(), arg) == single.end()) {
      throw std::invalid_argument("unknown argument '" + arg + "'");
    }
    if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
    const std::string& value = args[++i];
    if (arg == "--gripper-joint") {
      gripper.joints.push_back(value);
    } else if (arg == "--pad-link") {
      gripper.pad_links.push_back(value);
    } else if (arg == "--open") {
      gripper.open.insert(parsePosition(arg, value));
    } else if (arg == "--closed") {
      gripper.closed.insert(parsePosition(arg, value));
    } else {
      values[arg] = value;
    }
    gripper_given = gripper_given || repeated || arg == "--gripper-parent" || arg == "--closing-direction" ||
                    arg == "--tcp" || arg == "--tcp-parent";
  }
  if (!values.count("--urdf")) throw std::invalid_argument("--urdf is required");
  const bool repair = values.count("--urdf-out") || values.count("--repairs");
  if (repair) {
    if (!values.count("--urdf-out") || !values.count("--repairs")) {
      throw std::invalid_argument("--urdf-out and --repairs go together");
    }
    if (values.count("--srdf-out") || values.count("--describe") || values.count("--srdf-in")) {
      throw std::invalid_argument("--urdf-out/--repairs cannot be combined with --srdf-in, --srdf-out or --describe");
    }
    command.urdf_out_path = values["--urdf-out"];
    command.repairs_path = values["--repairs"];
    if (values.count("--inertia-density")) {
      command.repair.density = parseNumbers("--inertia-density", values["--inertia-density"], 1)[0];
      if (!(command.repair.density > 0.0)) throw std::invalid_argument("--inertia-density must be > 0");
    }
    if (gripper_given) {
      if (!values.count("--gripper-parent") || gripper.joints.empty()) {
        throw std::invalid_argument("the gripper options need --gripper-parent and at least one --gripper-joint");
      }
      gripper.parent_link = values["--gripper-parent"];
      if (values.count("--closing-direction")) {
        const auto v = parseNumbers("--closing-direction", values["--closing-direction"], 3);
        gripper.closing_direction = Eigen::Vector3d(v[0], v[1], v[2]);
      }
      if (values.count("--tcp")) {
        const auto v = parseNumbers("--tcp", values["--tcp"], 6);
        gripper.tcp = poseFromXyzRpy(v[0], v[1], v[2], v[3], v[4], v[5]);
      }
      if (values.count("--tcp-parent")) {
        if (!values.count("--tcp")) throw std::invalid_argument("--tcp-parent needs --tcp");
        gripper.tcp_parent = values["--tcp-parent"];
      }
      command.repair.gripper = gripper;
    }
    command.urdf_path = values["--urdf"];
    return command;
  }
  if (values.count("--inertia-density") || gripper_given) {
    throw std::invalid_argument("--inertia-density and the gripper options belong to the --urdf-out mode");
  }
  if (!values.count("--srdf-out") && !values.count("--describe")) {
    throw std::invalid_argument("--srdf-out, --describe or --urdf-out is required");
  }
  command.urdf_path = values["--urdf"];
  command.srdf_out_path = values["--srdf-out"];
  command.describe_path = values["--describe"];
  if (values.count("--srdf-in")) command.srdf_in_path = values["--srdf-in"];
  if (values.count("--density")) {
    unsigned long long density = 0;
    if (!parseWholeNumber(values["--density"], density) || density == 0) {
      throw std::invalid_argument("--density must be a whole number > 0, got '" + values["--density"] + "'");
    }
    command.options.collision.density = density;
  }
  if (values.count("--seed")) {
    unsigned long long seed = 0;
    if (!parseWholeNumber(values["--seed"], seed)) {
      throw std::invalid_argument("--seed must be a whole number >= 0, got '" + values["--seed"] + "'");
    }
    command.options.collision.seed = seed;
  }
  return command;
}

}  // namespace sixdof_core
