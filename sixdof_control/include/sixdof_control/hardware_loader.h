#pragma once

#include <pluginlib/class_loader.hpp>
#include <string>
#include <vector>

#include "sixdof_control/hardware_interface.h"

namespace sixdof_control {

// Loads hardware plugins through pluginlib: every package that exports a plugin of base class
// sixdof_control::HardwareInterface (package.xml: <export><sixdof_control plugin="${prefix}/plugins.xml"/></export>).
// The loader must outlive the plugins it made.
class HardwareLoader {
 public:
  HardwareLoader();

  // `name` is a declared class ("sixdof_control/mock"), or a name without package for sixdof_control's own
  // ("mock", "dynamixel"). Throws std::invalid_argument naming the plugin, why, and the declared ones.
  pluginlib::UniquePtr<HardwareInterface> load(const std::string& name);
  std::vector<std::string> declared();

 private:
  pluginlib::ClassLoader<HardwareInterface> loader_;
};

}  // namespace sixdof_control
