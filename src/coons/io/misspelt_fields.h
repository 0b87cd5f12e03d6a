// Fields of an input document that are one edit from a field the reader knows (misspelt_fields):
// ignored like any field of the reader's own, and worth a warning.
// Sizes: O(keys · known · length).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace coons {

//! A field of a document that is none of the reader's but one edit from one of them: the same
//! letters in another case, or one letter inserted, deleted, changed or two neighbours swapped
//! ("fre" for "free", "ring" for "rings", "knots_U" for "knots_u"). The formats allow fields of
//! their own, so such a field is not an error; the commands warn about it, since the file then
//! describes another problem than the one its author meant.
struct MisspeltField {
  std::string given, known;
};

//! The misspelt fields among the keys of `doc` (an object; nothing otherwise), in key order; keys
//! of fewer than 3 characters, and keys that are in `known`, are never misspelt.
std::vector<MisspeltField> misspelt_fields(const nlohmann::json& doc, const std::vector<std::string>& known);

}  // namespace coons
