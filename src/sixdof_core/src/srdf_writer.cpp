#include "sixdof_core/srdf_writer.h"

#include <tinyxml2.h>

#include <sstream>

namespace sixdof_core {

namespace {

XmlElement toElement(const tinyxml2::XMLElement* e) {
  XmlElement element;
  element.name = e->Name();
  for (const auto* a = e->FirstAttribute(); a; a = a->Next()) element.attributes.emplace_back(a->Name(), a->Value());
  for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) element.children.push_back(toElement(c));
  return element;
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void writeElement(std::ostream& out, const XmlElement& element, int depth) {
  const std::string indent(2 * depth, ' ');
  out << indent << '<' << element.name;
  for (const auto& [key, value] : element.attributes) out << ' ' << key << "=\"" << escape(value) << '"';
  if (element.children.empty()) {
    out << "/>\n";
    return;
  }
  out << ">\n";
  for (const auto& child : element.children) writeElement(out, child, depth + 1);
  out << indent << "</" << element.name << ">\n";
}

}  // namespace

std::string XmlElement::attribute(const std::string& key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return v;
  }
  return "";
}

SrdfDocument parseSrdfDocument(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str()) != tinyxml2::XML_SUCCESS) {
    throw SrdfError(std::string("SRDF: XML error: ") + doc.ErrorStr());
  }
  SrdfDocument document;
  for (const auto* node = doc.FirstChild(); node && !node->ToElement(); node = node->NextSibling()) {
    if (const auto* comment = node->ToComment()) document.leading_comments.emplace_back(comment->Value());
  }
  const auto* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot") throw SrdfError("SRDF: root element is not <robot>");
  const char* name = robot->Attribute("name");
  if (!name || !*name) throw SrdfError("SRDF: <robot> has no 'name' attribute");
  document.robot_name = name;
  for (const auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string kind = e->Name();
    if (kind == "group") {
      document.groups.push_back(toElement(e));
    } else if (kind == "group_state") {
      document.group_states.push_back(toElement(e));
    } else if (kind == "end_effector") {
      document.end_effectors.push_back(toElement(e));
    } else if (kind == "virtual_joint") {
      document.virtual_joints.push_back(toElement(e));
    } else if (kind == "passive_joint") {
      document.passive_joints.push_back(toElement(e));
    } else if (kind == "disable_collisions") {
      const char* link1 = e->Attribute("link1");
      const char* link2 = e->Attribute("link2");
      if (!link1 || !link2 || !*link1 || !*link2) {
        throw SrdfError("SRDF: <disable_collisions> without link1/link2 (line " + std::to_string(e->GetLineNum()) +
                        ")");
      }
      const char* reason = e->Attribute("reason");
      document.disabled_collisions.push_back({link1, link2, reason ? reason : ""});
    } else {
      throw SrdfError("SRDF: unknown element <" + kind + "> (line " + std::to_string(e->GetLineNum()) + ")");
    }
  }
  return document;
}

std::string writeSrdf(const SrdfDocument& document) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n";
  for (const auto& comment : document.leading_comments) out << "<!--" << comment << "-->\n";
  out << "<robot name=\"" << escape(document.robot_name) << "\">\n";
  for (const auto* kind : {&document.groups, &document.group_states, &document.end_effectors,
                           &document.virtual_joints, &document.passive_joints}) {
    for (const auto& element : *kind) writeElement(out, element, 1);
  }
  for (const auto& pair : document.disabled_collisions) {
    XmlElement element{"disable_collisions", {{"link1", pair.link1}, {"link2", pair.link2}}, {}};
    if (!pair.reason.empty()) element.attributes.emplace_back("reason", pair.reason);
    writeElement(out, element, 1);
  }
  out << "</robot>\n";
  return out.str();
}

}  // namespace sixdof_core
