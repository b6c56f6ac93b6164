// The command line of `rosrun sixdof_core setup_assistant_core` (the C++ half of `setup_assistant`).
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sixdof_core/setup_assistant.h"

namespace sixdof_core {

const char* const kSetupAssistantUsage =
    "usage: setup_assistant_core --urdf FILE [--srdf-in FILE] (--srdf-out FILE | --describe FILE)\n"
    "                            [--describe FILE] [--density N] [--seed S] [--groups-skeleton]\n"
    "  The C++ half of `setup_assistant` (the command users run; it also expands xacro and generates\n"
    "  config packages). The URDF must be expanded (no xacro).\n"
    "  --urdf FILE         robot description (package:// meshes are found in the folders above the URDF,\n"
    "                      then via ROS_PACKAGE_PATH)\n"
    "  --srdf-in FILE      existing SRDF: groups, states, end effectors, virtual/passive joints and\n"
    "                      disable_collisions entries with other reasons than Adjacent/Default/Always/Never\n"
    "                      are kept\n"
    "  --srdf-out FILE     where to write the SRDF (may be the same file as --srdf-in)\n"
    "  --describe FILE     write the model (links, joints, limits, groups with the IK solver that fits,\n"
    "                      states, end effectors, collision counts) as YAML; without --srdf-out: of the\n"
    "                      URDF (+ --srdf-in) model, without sampling\n"
    "  --density N         random samples for Always/Never (1000 low .. 100000 high; default 10000)\n"
    "  --seed S            random seed (default 0); the same inputs and seed give the same file\n"
    "  --groups-skeleton   when the input has no groups: arm = chain root -> last revolute joint's child,\n"
    "                      gripper = the other movable joints, end effector 'hand'\n";

namespace {

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
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h") {
      command.help = true;
      return command;
    }
    if (arg == "--groups-skeleton") {
      command.options.groups_skeleton = true;
    } else if (arg == "--urdf" || arg == "--srdf-in" || arg == "--srdf-out" || arg == "--density" || arg == "--seed" ||
               arg == "--describe") {
      if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
      values[arg] = args[++i];
    } else {
      throw std::invalid_argument("unknown argument '" + arg + "'");
    }
  }
  if (!values.count("--urdf")) throw std::invalid_argument("--urdf is required");
  if (!values.count("--srdf-out") && !values.count("--describe")) {
    throw std::invalid_argument("--srdf-out or --describe is required");
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
