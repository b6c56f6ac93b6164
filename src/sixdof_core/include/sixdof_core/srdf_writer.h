#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sixdof_core {

// Thrown on an SRDF that is not well-formed XML or misses a required attribute; the message names the problem.
class SrdfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One SRDF element as written by hand: attributes in document order, child elements (SRDF has no text).
struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;

  // The attribute's value, or "" when it is absent.
  std::string attribute(const std::string& key) const;
};

struct SrdfCollisionPair {
  std::string link1;
  std::string link2;
  std::string reason;
};

// An SRDF document split into its element kinds. Hand-written elements are kept verbatim (attribute order
// and values as written) so that rewriting a file changes only what was recomputed.
struct SrdfDocument {
  std::string robot_name;
  std::vector<std::string> leading_comments;  // comment texts before <robot>, e.g. a generator's header
  std::vector<XmlElement> groups;
  std::vector<XmlElement> group_states;
  std::vector<XmlElement> end_effectors;
  std::vector<XmlElement> virtual_joints;
  std::vector<XmlElement> passive_joints;
  std::vector<SrdfCollisionPair> disabled_collisions;
};

// Throws SrdfError on malformed XML, a root other than <robot>, an unknown top-level element or a
// disable_collisions entry without link1/link2. Comments inside <robot> are not kept.
SrdfDocument parseSrdfDocument(const std::string& xml);

// Writes the elements kind by kind (groups, group_states, end_effectors, virtual_joints, passive_joints,
// disable_collisions), each kind in the document's order, two-space indentation, attribute values escaped.
// The same document always gives the same bytes.
std::string writeSrdf(const SrdfDocument& document);

}  // namespace sixdof_core
