// The boundary file beyond one ring: "rings" and "free" in the net form, "ribbons" with the sides,
// and the mask problem each form describes (stencil_problem).
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "coons/net/coons_net.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;

namespace {

// The sides and ribbons of a full net as a boundary file.
json ribbon_file(const ControlNet& net) {
  json doc = boundary_to_json(boundary_of(net, "ribbon"));
  const int m = net.m, n = net.n;
  json bottom = json::array(), top = json::array(), left = json::array(), right = json::array();
  auto point = [&](int i, int j) { return json{net.at(i, j)(0), net.at(i, j)(1), net.at(i, j)(2)}; };
  for (int i = 0; i <= m; ++i) {
    bottom.push_back(point(i, 1));
    top.push_back(point(i, n - 1));
  }
  for (int j = 0; j <= n; ++j) {
    left.push_back(point(1, j));
    right.push_back(point(m - 1, j));
  }
  doc["ribbons"] = {{"bottom", bottom}, {"top", top}, {"left", left}, {"right", right}};
  return doc;
}

// The InputError's message for `doc` ("" when it parses).
std::string error_of(const json& doc) {
  try {
    (void)parse_boundary(doc, "b.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

json zero_grid(int m, int n) {
  return json(std::vector<std::vector<int>>(std::size_t(m) + 1, std::vector<int>(std::size_t(n) + 1, 0)));
}

}  // namespace

TEST_CASE("stencil_problem: ribbons give a net whose two outer rings are the data", "[io]") {
  const ControlNet net = make_random_net(6, 5, 11);
  const BoundaryFile f = parse_boundary(json::parse(ribbon_file(net).dump()), "b.json");
  REQUIRE(f.ribbons);
  CHECK(f.rings == 2);
  CHECK(!is_classical(f));
  const StencilProblem p = stencil_problem(f);
  CHECK(p.rings == 2);
  CHECK(p.free.size() == 0);
  REQUIRE(p.net.m == 6);
  REQUIRE(p.net.n == 5);
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 5; ++j)
      if (std::min({i, j, 6 - i, 5 - j}) < 2) CHECK(p.net.at(i, j) == net.at(i, j));
  // start values inside: the discrete Coons net of the inner ring
  Boundary ring;
  ring.m = 4;
  ring.n = 3;
  ring.bottom = ring.top = Eigen::MatrixX3d(5, 3);
  ring.left = ring.right = Eigen::MatrixX3d(4, 3);
  for (int i = 0; i <= 4; ++i) {
    ring.bottom.row(i) = net.at(i + 1, 1);
    ring.top.row(i) = net.at(i + 1, 4);
  }
  for (int j = 0; j <= 3; ++j) {
    ring.left.row(j) = net.at(1, j + 1);
    ring.right.row(j) = net.at(5, j + 1);
  }
  const ControlNet start = discrete_coons_net(ring);
  for (int i = 2; i <= 4; ++i)
    for (int j = 2; j <= 3; ++j) CHECK(p.net.at(i, j) == start.at(i - 1, j - 1));
}

TEST_CASE("stencil_problem: sides alone are the classical problem, the net form keeps rings and free", "[io]") {
  const Boundary b = make_random_boundary(4, 3, 2);
  const BoundaryFile sides = parse_boundary(boundary_to_json(b), "b.json");
  CHECK(is_classical(sides));
  const StencilProblem p1 = stencil_problem(sides);
  CHECK(p1.rings == 1);
  CHECK(p1.net.points == discrete_coons_net(b).points);

  const ControlNet net = make_random_net(5, 5, 3);
  json doc = {{"net", net_to_json(net)}, {"rings", 2}};
  json free = zero_grid(5, 5);
  free[2][2] = 1;
  free[3][2] = 1;
  doc["free"] = free;
  const BoundaryFile f = parse_boundary(json::parse(doc.dump()), "n.json");
  CHECK(f.rings == 2);
  CHECK(!is_classical(f));
  const StencilProblem p2 = stencil_problem(f);
  CHECK(p2.rings == 2);
  CHECK(p2.net.points == net.points);
  REQUIRE(p2.free.rows() == 6);
  CHECK(p2.free.count() == 2);
  CHECK(p2.free(3, 2));
  CHECK(!p2.free(2, 3));
  // a net with only "rings": the inside of the rings is free (free_points)
  const BoundaryFile r = parse_boundary(json{{"net", net_to_json(net)}, {"rings", 3}}, "n.json");
  CHECK(r.rings == 3);
  CHECK(free_points(stencil_problem(r)).count() == 0);
}

TEST_CASE("parse_boundary: bad rings, free grids and ribbons name the field and the point", "[io]") {
  const ControlNet net = make_random_net(6, 6, 5);
  SECTION("rings") {
    CHECK(error_of(json{{"net", net_to_json(net)}, {"rings", 0}}).rfind("b.json: rings: ", 0) == 0);
    CHECK(error_of(json{{"net", net_to_json(net)}, {"rings", 1.5}}).rfind("b.json: rings: ", 0) == 0);
    CHECK_THAT(error_of(json{{"net", net_to_json(net)}, {"rings", 5}}), Catch::Contains("has only 4"));
    CHECK_THAT(error_of(json{{"bottom", json::array()}, {"rings", 2}}), Catch::StartsWith("b.json: rings: "));
  }
  SECTION("free") {
    json doc = {{"net", net_to_json(net)}, {"rings", 2}, {"free", zero_grid(6, 6)}};
    doc["free"][1][3] = 1;  // in the second data ring: free all the same (the mask checks its stencil)
    CHECK(parse_boundary(doc, "b.json").free(1, 3));
    doc["free"][1][3] = 2;
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: free[1][3]: "));
    doc["free"][1][3] = 0;
    doc["free"].erase(6);
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: free: "));
    json sides = ribbon_file(net);
    sides["free"] = zero_grid(6, 6);
    CHECK_THAT(error_of(sides), Catch::StartsWith("b.json: free: belongs to the \"net\" form"));
  }
  SECTION("ribbons") {
    const json good = ribbon_file(net);
    CHECK(error_of(good).empty());
    json doc = good;
    doc["ribbons"].erase("right");
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.right: missing"));
    doc = good;
    doc["ribbons"]["top"].erase(0);
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.top: has 6 points"));
    doc = good;
    doc["ribbons"]["left"][2] = {1, 2};
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.left[2]: "));
    doc = good;
    doc["ribbons"]["left"][1][0] = doc["ribbons"]["left"][1][0].get<double>() + 1e-3;  // b[1][1]
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.left[1]: is the same net point as ribbons.bottom[1]"));
    doc = good;
    doc["ribbons"]["right"][6][2] = doc["ribbons"]["right"][6][2].get<double>() + 1e-3;  // b[5][6]
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.right[6]: is the same net point as top[5]"));
    doc = good;
    doc["ribbons"]["bottom"][0][1] = doc["ribbons"]["bottom"][0][1].get<double>() - 1e-3;  // b[0][1]
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons.bottom[0]: is the same net point as left[1]"));
    doc = good;
    doc["ribbons"] = json::array();
    CHECK_THAT(error_of(doc), Catch::StartsWith("b.json: ribbons: must be an object"));
    json net_form = {{"net", net_to_json(net)}, {"ribbons", good["ribbons"]}};
    CHECK_THAT(error_of(net_form), Catch::StartsWith("b.json: ribbons: belongs to the sides form"));
    json small = ribbon_file(make_random_net(3, 6, 1));
    CHECK_THAT(error_of(small), Catch::StartsWith("b.json: ribbons: need degree >= 4"));
  }
}

TEST_CASE("parse_boundary: ribbon points that agree within the corner tolerance are accepted", "[io]") {
  json doc = ribbon_file(make_random_net(4, 4, 8));
  doc["ribbons"]["left"][1][0] = doc["ribbons"]["left"][1][0].get<double>() + 1e-13;
  CHECK(error_of(doc).empty());
  BoundaryReadOptions strict;
  strict.corner_tolerance = 1e-15;
  CHECK_THROWS_AS(parse_boundary(doc, "b.json", strict), InputError);
}

TEST_CASE("parse_boundary: a B-spline solve report is refused naming bspline and not read as a Bezier net", "[io]") {
  // coons solve writes "net" (the B-spline control net) and a "bspline" block (knots, degrees) for
  // a B-spline boundary; read back as a net file it used to be solved as a Bezier net.
  const ControlNet net = make_random_net(7, 6, 4);
  json report = {{"net", net_to_json(net)}, {"degree", {7, 6}}};
  REQUIRE(error_of(report).empty());
  report["bspline"] = {{"degree_spline", {3, 3}}, {"knots_u", {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}}};
  CHECK_THAT(error_of(report), Catch::StartsWith("b.json: bspline: a B-spline solve report"));
  json knots = {{"net", net_to_json(net)}, {"knots_u", {0, 1}}};
  CHECK_THAT(error_of(knots), Catch::StartsWith("b.json: knots_u: belongs to the sides form"));
}
