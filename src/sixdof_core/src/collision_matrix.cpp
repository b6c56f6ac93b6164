#include "sixdof_core/collision_matrix.h"

#include <set>

namespace sixdof_core {

AllowedCollisionMatrix AllowedCollisionMatrix::fromDisabledPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs) {
  AllowedCollisionMatrix acm;
  for (const auto& [a, b] : pairs) acm.setEntry(a, b, true);
  return acm;
}

std::pair<std::string, std::string> AllowedCollisionMatrix::key(const std::string& a, const std::string& b) {
  return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
}

void AllowedCollisionMatrix::setEntry(const std::string& a, const std::string& b, bool allowed) {
  entries_[key(a, b)] = allowed;
}

void AllowedCollisionMatrix::removeEntry(const std::string& a, const std::string& b) { entries_.erase(key(a, b)); }

void AllowedCollisionMatrix::setDefaultEntry(const std::string& name, bool allowed) { defaults_[name] = allowed; }

void AllowedCollisionMatrix::removeDefaultEntry(const std::string& name) { defaults_.erase(name); }

void AllowedCollisionMatrix::removeName(const std::string& name) {
  defaults_.erase(name);
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->first.first == name || it->first.second == name) {
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
}

std::optional<bool> AllowedCollisionMatrix::entry(const std::string& a, const std::string& b) const {
  auto it = entries_.find(key(a, b));
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

std::optional<bool> AllowedCollisionMatrix::defaultEntry(const std::string& name) const {
  auto it = defaults_.find(name);
  if (it == defaults_.end()) return std::nullopt;
  return it->second;
}

bool AllowedCollisionMatrix::isAllowed(const std::string& a, const std::string& b) const {
  if (auto e = entry(a, b)) return *e;
  auto da = defaultEntry(a);
  auto db = defaultEntry(b);
  return (da && *da) || (db && *db);
}

std::vector<std::string> AllowedCollisionMatrix::names() const {
  std::set<std::string> all;
  for (const auto& [k, v] : entries_) {
    all.insert(k.first);
    all.insert(k.second);
  }
  for (const auto& [k, v] : defaults_) all.insert(k);
  return {all.begin(), all.end()};
}

}  // namespace sixdof_core
