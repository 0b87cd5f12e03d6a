#include "misspelt_fields.h"

#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>

namespace coons {

namespace {

char lower(char c) { return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c; }

bool same_but_case(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (lower(a[k]) != lower(b[k])) return false;
  return true;
}

// One insertion, deletion, substitution or swap of neighbours (optimal string alignment distance 1).
bool one_edit_apart(const std::string& a, const std::string& b) {
  if (a == b) return false;
  const std::string& s = a.size() <= b.size() ? a : b;  // the shorter
  const std::string& l = a.size() <= b.size() ? b : a;
  if (l.size() - s.size() > 1) return false;
  std::size_t k = 0;
  while (k < s.size() && s[k] == l[k]) ++k;
  if (s.size() < l.size()) return s.compare(k, std::string::npos, l, k + 1, std::string::npos) == 0;
  if (s.compare(k + 1, std::string::npos, l, k + 1, std::string::npos) == 0) return true;  // changed
  return k + 1 < s.size() && s[k] == l[k + 1] && s[k + 1] == l[k] &&                       // swapped
         s.compare(k + 2, std::string::npos, l, k + 2, std::string::npos) == 0;
}

}  // namespace

std::vector<MisspeltField> misspelt_fields(const nlohmann::json& doc, const std::vector<std::string>& known) {
  std::vector<MisspeltField> out;
  if (!doc.is_object()) return out;
  for (const auto& item : doc.items()) {
    const std::string& key = item.key();
    if (key.size() < 3 || std::find(known.begin(), known.end(), key) != known.end()) continue;
    for (const std::string& k : known)
      if (same_but_case(key, k) || one_edit_apart(key, k)) {
        out.push_back({key, k});
        break;
      }
  }
  return out;
}

}  // namespace coons
