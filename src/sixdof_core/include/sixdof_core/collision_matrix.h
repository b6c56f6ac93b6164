#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sixdof_core {

// Which pairs of bodies (robot links, attached or world objects, by name) may touch.
// Lookup order follows MoveIt's: an explicit pair entry wins; otherwise the pair is allowed when
// either body has a default entry that allows it; otherwise the pair is checked.
// The matrix itself knows no geometry; CollisionScene validates names when entries are set through it.
class AllowedCollisionMatrix {
 public:
  AllowedCollisionMatrix() = default;

  // One entry per SRDF disable_collisions pair (link1, link2).
  static AllowedCollisionMatrix fromDisabledPairs(const std::vector<std::pair<std::string, std::string>>& pairs);

  void setEntry(const std::string& a, const std::string& b, bool allowed);
  void removeEntry(const std::string& a, const std::string& b);
  void setDefaultEntry(const std::string& name, bool allowed);
  void removeDefaultEntry(const std::string& name);
  // Removes every pair entry and the default entry that mention `name`.
  void removeName(const std::string& name);

  std::optional<bool> entry(const std::string& a, const std::string& b) const;
  std::optional<bool> defaultEntry(const std::string& name) const;
  bool isAllowed(const std::string& a, const std::string& b) const;

  // Every name that appears in a pair or default entry (sorted, unique).
  std::vector<std::string> names() const;
  std::size_t size() const { return entries_.size(); }

 private:
  static std::pair<std::string, std::string> key(const std::string& a, const std::string& b);

  std::map<std::pair<std::string, std::string>, bool> entries_;
  std::map<std::string, bool> defaults_;
};

}  // namespace sixdof_core
