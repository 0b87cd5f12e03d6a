#include "coons/io/bspline_boundary_io.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;

namespace {

// Degree (3, 2), 6 points along u, 5 along v.
json valid_fields() {
  return json{{"degree_spline", {3, 2}},
              {"knots_u", {0, 0, 0, 0, 0.25, 0.7, 1, 1, 1, 1}},
              {"knots_v", {-1, -1, -1, 0.5, 0.5, 2, 2, 2}}};
}

// The field of the InputError parse_bspline_knots throws on doc, or "" when it accepts it.
std::string rejected_field(const json& doc) {
  try {
    (void)parse_bspline_knots(doc, "b.json", 6, 5);
  } catch (const InputError& e) {
    CHECK(e.file() == "b.json");
    CHECK_FALSE(e.reason().empty());
    return e.field();
  }
  return "";
}

}  // namespace

TEST_CASE("parse_bspline_knots: reads the three fields, absent fields mean a Bézier file", "[io][bspline]") {
  const auto knots = parse_bspline_knots(valid_fields(), "b.json", 6, 5);
  REQUIRE(knots.has_value());
  CHECK(knots->degree_u == 3);
  CHECK(knots->degree_v == 2);
  CHECK(knots->knots_u.size() == 10);
  CHECK(knots->knots_v(3) == 0.5);
  CHECK_FALSE(parse_bspline_knots(json{{"m", 3}}, "b.json", 6, 5).has_value());
}

TEST_CASE("parse_bspline_knots: every bad knot vector is an input error naming the field and index", "[io][bspline]") {
  json doc = valid_fields();
  SECTION("decreasing") {
    doc["knots_u"][5] = 0.1;
    CHECK(rejected_field(doc) == "knots_u[5]");
  }
  SECTION("not clamped") {
    doc["knots_v"][2] = -0.5;
    CHECK(rejected_field(doc) == "knots_v[2]");
  }
  SECTION("interior knot above the degree") {
    doc["degree_spline"] = {1, 2};
    doc["knots_u"] = {0, 0, 0.3, 0.5, 0.5, 0.7, 1, 1};
    CHECK(rejected_field(doc) == "knots_u[4]");
  }
  SECTION("wrong length") {
    doc["knots_u"] = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
    CHECK(rejected_field(doc) == "knots_u");
  }
  SECTION("not a number") {
    doc["knots_u"][4] = "a";
    CHECK(rejected_field(doc) == "knots_u[4]");
  }
  SECTION("bad degrees") {
    doc["degree_spline"] = {0, 2};
    CHECK(rejected_field(doc) == "degree_spline[0]");
    doc["degree_spline"] = 3;
    CHECK(rejected_field(doc) == "degree_spline");
  }
  SECTION("one field without the others") {
    doc.erase("knots_v");
    CHECK(rejected_field(doc) == "knots_v");
  }
}

TEST_CASE("bspline_boundary: the sides on the parsed knots give the Greville Coons surface", "[io][bspline]") {
  const auto knots = parse_bspline_knots(valid_fields(), "b.json", 6, 5);
  REQUIRE(knots.has_value());
  const Boundary frame = make_random_boundary(5, 4, 6100U);
  const BSplineBoundary b = bspline_boundary(frame, *knots);
  CHECK(b.bottom.is_valid(nullptr));
  CHECK(b.right.is_valid(nullptr));
  const BSplineSurface s = greville_coons_surface(compatible_boundary(b));
  for (int k = 0; k <= 10; ++k)
    for (int l = 0; l <= 10; ++l)
      CHECK((evaluate(s, k / 10.0, l / 10.0) - coons_patch_point(b, k / 10.0, l / 10.0)).norm() < 1e-12);
}

TEST_CASE("parse_bspline_knots: per-side knot vectors, each checked under its own field", "[io][bspline]") {
  json doc = valid_fields();
  doc["knots_v"] = {{"left", {-1, -1, -1, 0.5, 0.5, 2, 2, 2}}, {"right", {0, 0, 0, 0.2, 0.3, 1, 1, 1}}};
  const auto knots = parse_bspline_knots(doc, "b.json", 6, 5);
  REQUIRE(knots.has_value());
  CHECK(knots->knots_v(3) == 0.5);
  CHECK(knots->knots_right(3) == 0.2);
  CHECK(knots->knots_top.size() == 0);
  doc["knots_v"]["right"][4] = 0.1;
  CHECK(rejected_field(doc) == "knots_v.right[4]");
  doc["knots_v"].erase("right");
  CHECK(rejected_field(doc) == "knots_v.right");
  doc["knots_v"]["middle"] = {0, 1};
  CHECK(rejected_field(doc) == "knots_v.middle");
}

TEST_CASE("parse_boundary: a B-spline file gives compatible sides and a note per changed side", "[io][bspline]") {
  const ControlNet net = make_random_net(5, 4, 9);
  json doc = boundary_to_json(boundary_of(net, "b"));
  doc["degree_spline"] = {3, 2};
  doc["knots_u"] = {{"bottom", {0, 0, 0, 0, 0.25, 0.7, 1, 1, 1, 1}}, {"top", {0, 0, 0, 0, 0.5, 0.6, 1, 1, 1, 1}}};
  doc["knots_v"] = {0, 0, 0, 0.5, 0.5, 1, 1, 1};
  const BoundaryFile file = parse_boundary(doc, "b.json");
  REQUIRE(file.bspline.has_value());
  const BSplineInput& in = *file.bspline;
  CHECK(in.notes.size() == 2);  // bottom and top each receive the other's two interior knots
  CHECK(in.compatible.bottom.count() == 8);
  CHECK(in.compatible.top.knots == in.compatible.bottom.knots);
  for (const double t : {0.0, 0.3, 0.55, 0.9, 1.0}) {
    CHECK((evaluate(in.compatible.top, t) - evaluate(in.given.top, t)).norm() < 1e-13);
    CHECK((evaluate(in.compatible.bottom, t) - evaluate(in.given.bottom, t)).norm() < 1e-13);
  }
  json with_net = json{{"net", net_to_json(net)}, {"knots_u", {0, 1}}};
  CHECK_THROWS_AS(parse_boundary(with_net, "n.json"), InputError);
}
