#pragma once
// Helpers the simulator's benchmarks share: the install space's share directory and the command line.

#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <utility>

namespace sixdof_sim::bench {

// The install space's share directory: <prefix>/lib/sixdof_sim/<benchmark> -> <prefix>/share.
inline std::filesystem::path shareDir() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().parent_path().parent_path() / "share";
}

// A benchmark's options: `--name value` into the variable registered under the name, a bare `--flag` sets its
// bool. The robot and world options every benchmark takes are registered from the start.
class CommandLine {
 public:
  CommandLine() {
    text("--urdf", "FILE", &urdf_path);
    text("--world", "FILE", &world_path);
    text("--package-root", "DIR", &package_root);
  }

  void text(const std::string& name, const std::string& metavar, std::string* value) {
    add(name, metavar, [value](const std::string& v) { *value = v; });
  }
  void number(const std::string& name, const std::string& metavar, double* value) {
    add(name, metavar, [value](const std::string& v) { *value = std::stod(v); });
  }
  void number(const std::string& name, const std::string& metavar, int* value) {
    add(name, metavar, [value](const std::string& v) { *value = std::stoi(v); });
  }
  void flag(const std::string& name, bool* value) {
    flags_[name] = value;
    usage_ += " [" + name + "]";
  }

  // False for an unknown option, a missing value or one that is not a number (then see usage()).
  // Then the robot and world default to the installed sixdof_description URDF and sixdof_sim's table_top.yaml.
  bool parse(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (flags_.count(arg) != 0) {
        *flags_[arg] = true;
        continue;
      }
      const auto option = options_.find(arg);
      if (option == options_.end() || i + 1 >= argc) return false;
      try {
        option->second(argv[++i]);
      } catch (const std::exception&) {
        return false;
      }
    }
    if (urdf_path.empty()) urdf_path = (shareDir() / "sixdof_description" / "urdf" / "sixdof.urdf").string();
    if (world_path.empty()) world_path = (shareDir() / "sixdof_sim" / "worlds" / "table_top.yaml").string();
    return true;
  }

  // Prints the options in the order they were registered; the exit code of a usage error.
  int usage(const char* argv0) const {
    std::cerr << "usage: " << argv0 << usage_ << "\n";
    return 2;
  }

  std::string urdf_path;
  std::string world_path;
  std::string package_root;  // empty: the install space's share directory

 private:
  void add(const std::string& name, const std::string& metavar, std::function<void(const std::string&)> parse) {
    options_[name] = std::move(parse);
    usage_ += " [" + name + " " + metavar + "]";
  }

  std::map<std::string, std::function<void(const std::string&)>> options_;
  std::map<std::string, bool*> flags_;
  std::string usage_;
};

}  // namespace sixdof_sim::bench
