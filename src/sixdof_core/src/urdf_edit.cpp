#include "sixdof_core/urdf_edit.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "sixdof_core/kinematics.h"

// The edits splice text at the elements tinyxml2 locates (it reports the line an element starts on): a parse and
// re-print would re-indent and re-quote the whole description.

namespace sixdof_core {

namespace {

struct Tag {
  size_t begin = std::string::npos;  // '<'
  size_t end = std::string::npos;    // one past '>'
  bool self_closing = false;
};

size_t lineStart(const std::string& text, int line) {
  size_t offset = 0;
  for (int l = 1; l < line && offset != std::string::npos; ++l) {
    offset = text.find('\n', offset);
    if (offset != std::string::npos) ++offset;
  }
  return offset == std::string::npos ? text.size() : offset;
}

// The value of attribute `name` in a start tag's text ("" when absent).
std::string attribute(const std::string& tag, const std::string& name) {
  for (size_t at = tag.find(name); at != std::string::npos; at = tag.find(name, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(tag[at - 1]))) continue;
    size_t i = at + name.size();
    while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
    if (i >= tag.size() || tag[i] != '=') continue;
    ++i;
    while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
    if (i >= tag.size() || (tag[i] != '"' && tag[i] != '\'')) continue;
    const size_t close = tag.find(tag[i], i + 1);
    if (close != std::string::npos) return tag.substr(i + 1, close - i - 1);
  }
  return "";
}

// The first start tag <element ...> at or after `from` (outside comments) whose `name` attribute is `name` (any
// name when empty).
Tag findStartTag(const std::string& text, size_t from, const std::string& element, const std::string& name) {
  const std::string open = "<" + element;
  for (size_t i = from; i < text.size();) {
    if (text.compare(i, 4, "<!--") == 0) {
      const size_t close = text.find("-->", i + 4);
      i = close == std::string::npos ? text.size() : close + 3;
      continue;
    }
    if (text.compare(i, open.size(), open) == 0 && i + open.size() < text.size() &&
        (std::isspace(static_cast<unsigned char>(text[i + open.size()])) || text[i + open.size()] == '/' ||
         text[i + open.size()] == '>')) {
      char quote = 0;
      size_t j = i + open.size();
      for (; j < text.size(); ++j) {
        if (quote) {
          if (text[j] == quote) quote = 0;
        } else if (text[j] == '"' || text[j] == '\'') {
          quote = text[j];
        } else if (text[j] == '>') {
          break;
        }
      }
      if (j >= text.size()) break;
      const std::string tag = text.substr(i, j + 1 - i);
      if (name.empty() || attribute(tag, "name") == name) return Tag{i, j + 1, text[j - 1] == '/'};
      i = j + 1;
      continue;
    }
    ++i;
  }
  return Tag{};
}

// The whitespace before position `at` on its line.
std::string indentOf(const std::string& text, size_t at) {
  const size_t start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const size_t begin = start == std::string::npos ? 0 : start + 1;
  size_t end = begin;
  while (end < at && (text[end] == ' ' || text[end] == '\t')) ++end;
  return text.substr(begin, end - begin);
}

std::string inertialXml(const LinkInertial& inertial, const std::string& indent) {
  const Eigen::Vector3d c = inertial.origin.translation();
  const Eigen::Vector3d rpy = rpyFromRotation(inertial.origin.linear());
  const Eigen::Matrix3d& i = inertial.inertia;
  const std::string inner = indent + "  ";
  return indent + "<inertial>\n" + inner + "<origin xyz=\"" + urdfNumber(c.x()) + " " + urdfNumber(c.y()) + " " +
         urdfNumber(c.z()) + "\" rpy=\"" + urdfNumber(rpy.x()) + " " + urdfNumber(rpy.y()) + " " +
         urdfNumber(rpy.z()) + "\"/>\n" + inner + "<mass value=\"" + urdfNumber(inertial.mass) + "\"/>\n" + inner +
         "<inertia ixx=\"" + urdfNumber(i(0, 0)) + "\" ixy=\"" + urdfNumber(i(0, 1)) + "\" ixz=\"" +
         urdfNumber(i(0, 2)) + "\" iyy=\"" + urdfNumber(i(1, 1)) + "\" iyz=\"" + urdfNumber(i(1, 2)) + "\" izz=\"" +
         urdfNumber(i(2, 2)) + "\"/>\n" + indent + "</inertial>";
}

std::string frameXml(const UrdfFrame& frame, const std::string& indent) {
  const Eigen::Vector3d p = frame.origin.translation();
  const Eigen::Vector3d rpy = rpyFromRotation(frame.origin.linear());
  const std::string inner = indent + "  ";
  return indent + "<link name=\"" + frame.name + "\"/>\n" + indent + "<joint name=\"" + frame.joint +
         "\" type=\"fixed\">\n" + inner + "<parent link=\"" + frame.parent + "\"/>\n" + inner + "<child link=\"" +
         frame.name + "\"/>\n" + inner + "<origin xyz=\"" + urdfNumber(p.x()) + " " + urdfNumber(p.y()) + " " +
         urdfNumber(p.z()) + "\" rpy=\"" + urdfNumber(rpy.x()) + " " + urdfNumber(rpy.y()) + " " +
         urdfNumber(rpy.z()) + "\"/>\n" + indent + "</joint>\n";
}

struct Splice {
  size_t begin;
  size_t end;
  std::string text;
};

}  // namespace

std::string urdfNumber(double value) {
  if (std::abs(value) < 1e-15) return "0";
  char buffer[32];
  for (int precision = 1; precision <= 9; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::abs(std::strtod(buffer, nullptr) - value) <= 5e-10 * std::abs(value)) break;
  }
  return buffer;
}

std::string editUrdf(const std::string& urdf_xml, const UrdfEdits& edits) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw RobotModelError(std::string("URDF is not valid XML: ") + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") throw RobotModelError("URDF has no <robot> root element");
  std::vector<Splice> splices;
  for (const auto& [name, edit] : edits.inertials) {
    const tinyxml2::XMLElement* link = robot->FirstChildElement("link");
    while (link && (!link->Attribute("name") || name != link->Attribute("name"))) {
      link = link->NextSiblingElement("link");
    }
    if (!link) throw RobotModelError("URDF has no <link name=\"" + name + "\">");
    const Tag tag = findStartTag(urdf_xml, lineStart(urdf_xml, link->GetLineNum()), "link", name);
    if (tag.begin == std::string::npos) throw RobotModelError("URDF: cannot locate <link name=\"" + name + "\">");
    const std::string indent = indentOf(urdf_xml, tag.begin);
    const std::string child = indent + "  ";
    std::string text = edit.note;  // "--" may not appear in an XML comment
    for (size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) text.replace(at, 2, "- -");
    const std::string note = text.empty() ? "" : child + "<!-- " + text + " -->\n";
    const std::string block = note + inertialXml(edit.inertial, child);
    if (tag.self_closing) {
      const size_t slash = urdf_xml.rfind('/', tag.end - 1);
      splices.push_back({slash, tag.end, ">\n" + block + "\n" + indent + "</link>"});
      continue;
    }
    const tinyxml2::XMLElement* old = link->FirstChildElement("inertial");
    if (!old) {
      splices.push_back({tag.end, tag.end, "\n" + block});
      continue;
    }
    const Tag start = findStartTag(urdf_xml, std::max(lineStart(urdf_xml, old->GetLineNum()), tag.end), "inertial", "");
    size_t end = start.end;
    if (start.begin != std::string::npos && !start.self_closing) {
      end = urdf_xml.find("</inertial>", start.end);
      if (end != std::string::npos) end += std::strlen("</inertial>");
    }
    if (start.begin == std::string::npos || end == std::string::npos) {
      throw RobotModelError("URDF: cannot locate the <inertial> of link '" + name + "'");
    }
    // On a line of its own, the whole line is replaced; otherwise the element only.
    const size_t newline = urdf_xml.rfind('\n', start.begin);
    const size_t line = newline == std::string::npos ? 0 : newline + 1;
    const bool own_line = urdf_xml.find_first_not_of(" \t", line) == start.begin;
    const size_t begin = own_line ? line : start.begin;
    splices.push_back({begin, end, own_line ? block : block.substr(child.size())});
  }
  if (!edits.frames.empty()) {
    const size_t close = urdf_xml.rfind("</robot>");
    if (close == std::string::npos) throw RobotModelError("URDF has no </robot>");
    const size_t line = urdf_xml.rfind('\n', close);
    const bool own_line = line != std::string::npos && indentOf(urdf_xml, close).size() == close - line - 1;
    std::string text = own_line ? "" : "\n";
    for (const UrdfFrame& frame : edits.frames) text += frameXml(frame, "  ");
    const size_t at = own_line ? line + 1 : close;
    splices.push_back({at, at, text});
  }
  std::sort(splices.begin(), splices.end(), [](const Splice& a, const Splice& b) { return a.begin > b.begin; });
  std::string out = urdf_xml;
  for (const Splice& s : splices) out.replace(s.begin, s.end - s.begin, s.text);
  return out;
}

}  // namespace sixdof_core
