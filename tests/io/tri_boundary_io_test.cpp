#include "coons/io/tri_boundary_io.h"

#include <catch2/catch.hpp>
#include <string>

#include "coons/io/input_error.h"
#include "tri/tri_fixtures.h"

using namespace coons;
using namespace coons::tri;
using namespace coons::tri_test;
using nlohmann::json;

namespace {

// The InputError message of parsing `doc`, or "" when it parses.
std::string error_of(const json& doc) {
  try {
    parse_tri_boundary(doc, "T.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("parse_tri_boundary: the sides of tri_boundary_to_json read back exactly", "[io][tri]") {
  for (int n = 1; n <= 9; ++n) {
    const TriBoundary b = boundary_of(random_tri_net(n, 300 + n), "random");
    const json doc = json::parse(tri_boundary_to_json(b).dump());
    REQUIRE(is_triangle_document(doc));
    const TriBoundary back = parse_tri_boundary(doc, "T.json");
    REQUIRE(back.n == n);
    REQUIRE(back.name == "random");
    for (int s = 0; s < 3; ++s) REQUIRE(back.sides[s] == b.sides[s]);
  }
}

TEST_CASE("parse_tri_boundary: a corner that disagrees is named with both copies and the gap", "[io][tri]") {
  const TriBoundary b = boundary_of(random_tri_net(4, 7));
  json doc = tri_boundary_to_json(b);
  doc["sides"][1][0][2] = doc["sides"][1][0][2].get<double>() + 0.5;
  REQUIRE(error_of(doc).rfind("T.json: sides[1][0]: corner (0,4,0) differs from sides[0][4] by 0.5", 0) == 0);
  doc = tri_boundary_to_json(b);
  doc["sides"][0][0][0] = doc["sides"][0][0][0].get<double>() - 0.25;
  REQUIRE(error_of(doc).rfind("T.json: sides[0][0]: corner (4,0,0) differs from sides[2][4] by 0.25", 0) == 0);
  doc = tri_boundary_to_json(b);
  doc["sides"][2][0][1] = doc["sides"][2][0][1].get<double>() + 1e-3;
  REQUIRE(error_of(doc).rfind("T.json: sides[2][0]: corner (0,0,4) differs from sides[1][4]", 0) == 0);
}

TEST_CASE("parse_tri_boundary: side lengths, degree, points and type are checked field by field", "[io][tri]") {
  const json good = tri_boundary_to_json(boundary_of(random_tri_net(3, 8)));
  REQUIRE(error_of(good).empty());
  struct Case {
    std::function<void(json&)> spoil;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](json& d) { d.erase("sides"); }, "T.json: sides: missing"},
      {[](json& d) { d["sides"].erase(2); }, "T.json: sides: must be an array of 3 sides"},
      {[](json& d) { d["sides"][1].erase(1); }, "T.json: sides[1]: has 3 points, sides[0] has 4"},
      {[](json& d) { d["sides"][0] = json::array({d["sides"][0][0]}); }, "T.json: sides[0]: needs at least 2 points"},
      {[](json& d) { d["degree"] = 5; }, "T.json: degree: says 5 but the sides have 4 points (degree 3)"},
      {[](json& d) { d["degree"] = 2.5; }, "T.json: degree: must be an integer"},
      // the range names the real cap, not [1, 2147483647]
      {[](json& d) { d["degree"] = 0; }, "T.json: degree: must be an integer in [1, 40], not 0"},
      {[](json& d) {
         d["sides"][2][1] = json::array({1, 2});
       },
       "T.json: sides[2][1]: a point must have 3 coordinates"},
      {[](json& d) { d["sides"][2][2][1] = "x"; }, "T.json: sides[2][2]:"},
      {[](json& d) { d["name"] = 3; }, "T.json: name: must be a string"},
      {[](json& d) { d["type"] = "quad"; }, "T.json: type: must be \"triangle\""},
  };
  for (const auto& c : cases) {
    json doc = good;
    c.spoil(doc);
    const std::string message = error_of(doc);
    INFO(message);
    REQUIRE(message.rfind(c.expected, 0) == 0);
  }
}

TEST_CASE("parse_tri_boundary: degree kMaxTriDegree is read, one more is refused naming the bound", "[io][tri]") {
  // Above it the dense Gram matrices of the exact energies took minutes (degree 100) or ran out of
  // memory (400, exit 1) instead of a clear refusal
  const json at_bound = tri_boundary_to_json(boundary_of(random_tri_net(kMaxTriDegree, 9)));
  CHECK(error_of(at_bound).empty());
  json above = tri_boundary_to_json(boundary_of(random_tri_net(kMaxTriDegree + 1, 10)));
  CHECK(error_of(above) ==
        "T.json: degree: degree 41 is above 40, the largest for a triangular boundary (its exact "
        "energies use dense Gram matrices that grow as the degree^4)");
  above.erase("degree");
  CHECK(error_of(above).rfind("T.json: sides[0]: degree 41 is above 40", 0) == 0);
}

TEST_CASE("tri_net_to_json: net[k][j] is b[n-k-j][j][k]", "[io][tri]") {
  const TriNet net = random_tri_net(6, 11);
  const json rows = tri_net_to_json(net);
  REQUIRE(rows.size() == 7);
  for (int k = 0; k <= 6; ++k) {
    REQUIRE(rows[k].size() == size_t(6 - k + 1));
    for (int j = 0; j <= 6 - k; ++j)
      for (int c = 0; c < 3; ++c) REQUIRE(rows[k][j][c].get<double>() == net.at(6 - k - j, j, k)(c));
  }
}
