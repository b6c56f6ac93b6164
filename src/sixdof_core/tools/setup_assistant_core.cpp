// setup_assistant: computes an SRDF's disabled collision pairs (MoveIt Setup Assistant semantics) and writes
// the SRDF, keeping the hand-written parts of an existing one. Run `setup_assistant --help`.
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
    std::cerr << "setup_assistant: " << e.what() << "\n" << sixdof_core::kSetupAssistantUsage;
    return 2;
  }
  if (command.help) {
    std::cout << sixdof_core::kSetupAssistantUsage;
    return 0;
  }
  try {
    const auto start = std::chrono::steady_clock::now();
    const auto result = sixdof_core::runSetupAssistantOnFiles(command);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::map<std::string, int> counts;
    for (const auto& pair : result.collisions.disabled) ++counts[sixdof_core::reasonName(pair.reason)];
    std::cout << "link pairs with geometry: " << result.collisions.link_pairs << "\n";
    for (const char* reason : {"Adjacent", "Default", "Always", "Never"}) {
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
  } catch (const std::exception& e) {
    std::cerr << "setup_assistant: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
