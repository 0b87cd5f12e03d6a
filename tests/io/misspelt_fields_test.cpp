// Fields one edit from a known one (coons/io/misspelt_fields.h), and the boundary reader's use of it.
#include "coons/io/misspelt_fields.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coons/io/boundary_io.h"

using namespace coons;
using nlohmann::json;

namespace {
std::vector<std::string> given_of(const std::vector<MisspeltField>& found) {
  std::vector<std::string> out;
  out.reserve(found.size());
  for (const MisspeltField& f : found) out.push_back(f.given + "->" + f.known);
  return out;
}
}  // namespace

TEST_CASE("misspelt_fields: one insertion, deletion, change, swap or another case from a known field", "[io]") {
  const std::vector<std::string> known = {"free", "rings", "knots_u", "ribbons", "degree"};
  const json doc = {{"fre", 1},    {"ring", 1}, {"knots_U", 1}, {"ribbosn", 1}, {"degrea", 1},
                    {"freee", 1},  {"free", 1}, {"comment", 1}, {"weight", 1},  {"ab", 1},
                    {"DEGREE", 1}, {"rngs", 1}, {"frre", 1}};
  // json objects keep their keys sorted
  CHECK(given_of(misspelt_fields(doc, known)) ==
        std::vector<std::string>{"DEGREE->degree", "degrea->degree", "fre->free", "freee->free", "frre->free",
                                 "knots_U->knots_u", "ribbosn->ribbons", "ring->rings", "rngs->rings"});
  CHECK(misspelt_fields(json::array({1, 2}), known).empty());
  CHECK(misspelt_fields(json{{"rigns", 1}, {"fee", 1}}, {"rings", "free"}).size() == 2);
  // two edits are no misspelling: "weight" is not "right", "beta" not "net"
  CHECK(misspelt_fields(json{{"weight", 1}, {"beta", 1}, {"alpha", 1}}, {"right", "net", "name"}).empty());
}

TEST_CASE("parse_boundary: a field one edit from one it reads is kept as misspelt, the file still read", "[io]") {
  json doc = {{"bottom", {{0, 0, 0}, {1, 0, 0}}},
              {"top", {{0, 1, 0}, {1, 1, 0}}},
              {"left", {{0, 0, 0}, {0, 1, 0}}},
              {"right", {{1, 0, 0}, {1, 1, 0}}},
              {"descripton", "a typo in a field people read"},
              {"comment", "a field of the author's own"}};
  const BoundaryFile file = parse_boundary(doc, "square.json");
  CHECK(file.boundary.m == 1);
  REQUIRE(file.misspelt.size() == 1);
  CHECK(file.misspelt[0].given == "descripton");
  CHECK(file.misspelt[0].known == "description");
  doc.erase("descripton");
  CHECK(parse_boundary(doc, "square.json").misspelt.empty());
}
