#pragma once
// YAML scalars and flow sequences as the setup assistant's describe and repair outputs write them.

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace sixdof_core {

// A YAML double-quoted scalar: names may hold any character.
inline std::string yamlString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\x%02x", static_cast<unsigned char>(c));
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Shortest text that reads back as the same double (YAML: .inf / -.inf / .nan; an exponent gets a mantissa with
// a point, 1.0e-06, which YAML 1.1 readers such as PyYAML need to see a number).
inline std::string yamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  std::string text;
  for (int precision = 6; precision <= 17 && text.empty(); ++precision) {
    std::ostringstream out;
    out << std::setprecision(precision) << value;
    if (std::stod(out.str()) == value || precision == 17) text = out.str();
  }
  const size_t exponent = text.find('e');
  if (exponent != std::string::npos && text.find('.') == std::string::npos) text.insert(exponent, ".0");
  return text;
}

inline std::string yamlVector(const Eigen::Vector3d& v) {
  return "[" + yamlNumber(v.x()) + ", " + yamlNumber(v.y()) + ", " + yamlNumber(v.z()) + "]";
}

inline std::string yamlNames(const std::vector<std::string>& names) {
  std::string out = "[";
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + yamlString(names[i]);
  return out + "]";
}

}  // namespace sixdof_core
