// setup_assistant_core: the C++ half of `setup_assistant` (scripts/setup_assistant, which also expands xacro and
// generates config packages). Computes an SRDF's disabled collision pairs (MoveIt Setup Assistant semantics),
// writes the SRDF keeping the hand-written parts of an existing one, and describes the model as YAML.
// Run `setup_assistant_core --help`.
#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "sixdof_core/setup_assistant.h"

int main(int argc, char** argv) {
  sixdof_core::SetupAssistantCommand command;
  try {
    command = sixdof_core::parseSetupAssistantArguments(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::invalid_argument& e) {
    std::cerr << "setup_assistant: " << e.what() << "\n";
    return 2;
  }
  if (command.help) {
    std::cout << sixdof_core::kSetupAssistantUsage;
    return 0;
  }
  // Progress on stdout while sampling, so that a high density is visibly alive: at most every 0.5 s, and
  // the end.
  auto last_progress = std::chrono::steady_clock::now();
  command.options.collision.progress = [&last_progress](std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (done < total && now - last_progress < std::chrono::milliseconds(500)) return;
    last_progress = now;
    std::cout << "sampling self-collisions: " << done << " / " << total << " (" << (100 * done / total) << "%)"
              << std::endl;
  };
  try {
    const auto start = std::chrono::steady_clock::now();
    const auto result = sixdof_core::runSetupAssistantOnFiles(command);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!command.urdf_out_path.empty()) {
      std::cout << "wrote " << command.urdf_out_path << "\nwrote " << command.repairs_path << "\n";
      return 0;
    }
    if (command.srdf_out_path.empty()) {
      std::cout << "wrote " << command.describe_path << "\n";
      return 0;
    }
    std::map<std::string, int> counts;
    for (const auto& pair : result.collisions.disabled) ++counts[sixdof_core::reasonName(pair.reason)];
    std::cout << "link pairs with geometry: " << result.collisions.link_pairs << "\n";
    for (const char* reason : {"Adjacent", "Default", "Always", "Never", "Gripper"}) {
      std::cout << "  " << reason << ": " << counts[reason] << "\n";
    }
    std::cout << "  enabled (checked when planning): "
              << result.collisions.link_pairs - result.collisions.disabled.size() << "\n";
    if (result.manual_pairs_kept > 0) std::cout << "  kept hand-written entries: " << result.manual_pairs_kept << "\n";
    if (command.options.groups_skeleton && !result.skeleton_written) {
      std::cout << "groups skeleton not written: the input SRDF has groups\n";
    }
    if (result.skeleton_written) std::cout << "groups skeleton written\n";
    std::cout << "samples: " << result.collisions.samples << " (seed " << command.options.collision.seed
              << "), pairwise checks: " << result.collisions.pair_checks << ", time: " << seconds << " s\n";
    std::cout << "wrote " << command.srdf_out_path << "\n";
    if (!command.describe_path.empty()) std::cout << "wrote " << command.describe_path << "\n";
  } catch (const std::exception& e) {
    // One line naming the problem; bad input (unreadable or malformed URDF/SRDF, a state outside its
    // limits, an unknown link) is a usage error: exit code 2, as for bad arguments.
    std::string message = e.what();
    for (auto& c : message) {
      if (c == '\n') c = ' ';
    }
    std::cerr << "setup_assistant: " << message << "\n";
    return 2;
  }
  return 0;
}
