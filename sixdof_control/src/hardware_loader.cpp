#include "sixdof_control/hardware_loader.h"

#include <stdexcept>

namespace sixdof_control {

HardwareLoader::HardwareLoader() : loader_("sixdof_control", "sixdof_control::HardwareInterface") {}

std::vector<std::string> HardwareLoader::declared() { return loader_.getDeclaredClasses(); }

pluginlib::UniquePtr<HardwareInterface> HardwareLoader::load(const std::string& name) {
  const std::string lookup = name.find('/') == std::string::npos ? "sixdof_control/" + name : name;
  try {
    return loader_.createUniqueInstance(lookup);
  } catch (const pluginlib::PluginlibException& e) {
    std::string known;
    for (const std::string& c : declared()) known += (known.empty() ? "" : ", ") + c;
    throw std::invalid_argument("hardware plugin '" + name + "' cannot be loaded (" + e.what() +
                                "); declared: " + (known.empty() ? "none" : known));
  }
}

}  // namespace sixdof_control
