// Setup assistant on a 20-link robot (a 17-joint serial arm with a two-finger gripper, primitive shapes) at
// the default density 10,000: the self-collision matrix alone (runSetupAssistant), and the whole config package
// (`setup_assistant --package-out`, the Python front end with the C++ core), each run `runs` times.
//   setup_assistant_bench [runs (default 5)] [density (default 10000)]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sixdof_core/setup_assistant.h"

namespace {

constexpr int kArmJoints = 17;  // links: base_link, link1..link17 and two fingers = 20

std::string cylinderLink(const std::string& name, double radius, double length, bool inertia) {
  std::ostringstream out;
  const std::string geometry = "<origin xyz=\"0 0 " + std::to_string(length / 2) + "\"/><geometry><cylinder radius=\"" +
                               std::to_string(radius) + "\" length=\"" + std::to_string(length) + "\"/></geometry>";
  out << "  <link name=\"" << name << "\"><visual>" << geometry << "</visual><collision>" << geometry
      << "</collision>";
  if (inertia) {
    out << "<inertial><mass value=\"0.5\"/><inertia ixx=\"0.001\" ixy=\"0\" ixz=\"0\" iyy=\"0.001\" iyz=\"0\" "
           "izz=\"0.001\"/></inertial>";
  }
  out << "</link>\n";
  return out.str();
}

std::string twentyLinkUrdf() {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<robot name=\"twenty\">\n" << cylinderLink("base_link", 0.06, 0.1, false);
  std::string parent = "base_link";
  for (int j = 1; j <= kArmJoints; ++j) {
    const std::string link = "link" + std::to_string(j);
    out << cylinderLink(link, 0.04 - 0.001 * j, 0.1, true);
    out << "  <joint name=\"joint" << j << "\" type=\"revolute\"><parent link=\"" << parent << "\"/><child link=\""
        << link << "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"" << (j % 2 ? "0 0 1" : "0 1 0")
        << "\"/><limit lower=\"-2.5\" upper=\"2.5\" velocity=\"2\" effort=\"50\"/></joint>\n";
    parent = link;
  }
  for (const char* side : {"left", "right"}) {
    const std::string finger = std::string(side) + "_finger";
    out << "  <link name=\"" << finger << "\"><collision><origin xyz=\"0 0 0.03\"/><geometry><box size=\"0.01 0.01 "
        << "0.06\"/></geometry></collision><inertial><mass value=\"0.05\"/><inertia ixx=\"1e-5\" ixy=\"0\" ixz=\"0\" "
        << "iyy=\"1e-5\" iyz=\"0\" izz=\"1e-5\"/></inertial></link>\n";
    out << "  <joint name=\"" << finger << "_joint\" type=\"prismatic\"><parent link=\"" << parent
        << "\"/><child link=\"" << finger << "\"/><origin xyz=\"0 " << (side[0] == 'l' ? "0.01" : "-0.01")
        << " 0.1\"/><axis xyz=\"0 " << (side[0] == 'l' ? "1" : "-1")
        << " 0\"/><limit lower=\"0\" upper=\"0.03\" velocity=\"0.1\" effort=\"10\"/>"
        << (side[0] == 'r' ? "<mimic joint=\"left_finger_joint\"/>" : "") << "</joint>\n";
  }
  out << "</robot>\n";
  return out.str();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  const long density = argc > 2 ? std::atol(argv[2]) : 10000;
  if (runs < 1 || density < 1) {
    std::fprintf(stderr, "usage: setup_assistant_bench [runs >= 1] [density >= 1]\n");
    return 2;
  }
  namespace fs = std::filesystem;
  using Clock = std::chrono::steady_clock;
  const fs::path work = fs::temp_directory_path() / ("setup_assistant_bench." + std::to_string(getpid()));
  fs::create_directories(work);
  const std::string urdf = twentyLinkUrdf();
  std::ofstream(work / "twenty.urdf") << urdf;

  sixdof_core::SetupAssistantOptions options;
  options.collision.density = static_cast<std::size_t>(density);
  options.groups_skeleton = true;
  std::vector<double> core_seconds;
  sixdof_core::SetupAssistantOutput result;
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    result = sixdof_core::runSetupAssistant(urdf, "", options);
    core_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }

  // The front end, sixdof_setup_assistant, installed in the same prefix (lib/sixdof_setup_assistant beside this
  // executable's lib/sixdof_core).
  const fs::path script =
      fs::canonical("/proc/self/exe").parent_path().parent_path() / "sixdof_setup_assistant" / "setup_assistant";
  std::vector<double> package_seconds;
  bool package_ok = fs::exists(script);
  for (int r = 0; package_ok && r < runs; ++r) {
    fs::remove_all(work / "out");
    const std::string command = script.string() + " --urdf " + (work / "twenty.urdf").string() + " --package-out " +
                                (work / "out").string() + " --density " + std::to_string(density) + " > " +
                                (work / "log.txt").string() + " 2>&1";
    const auto start = Clock::now();
    package_ok = std::system(command.c_str()) == 0;
    package_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  fs::remove_all(work);

  std::printf("20-link robot (17 revolute joints, a two-finger gripper with a mimic finger), %zu link pairs with "
              "geometry, density %ld, %d runs each; wall-clock seconds.\n\n",
              result.collisions.link_pairs, density, runs);
  std::printf("| step | median s | max s |\n|---|---:|---:|\n");
  std::printf("| collision matrix (core, %zu pairwise checks) | %.3f | %.3f |\n", result.collisions.pair_checks,
              median(core_seconds), *std::max_element(core_seconds.begin(), core_seconds.end()));
  if (package_ok && !package_seconds.empty()) {
    std::printf("| whole package (`setup_assistant --package-out`) | %.3f | %.3f |\n", median(package_seconds),
                *std::max_element(package_seconds.begin(), package_seconds.end()));
  } else {
    std::printf("| whole package (`setup_assistant --package-out`) | failed (%s) | |\n", script.c_str());
    return 1;
  }
  return 0;
}
