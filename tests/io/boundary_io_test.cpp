#include "coons/io/boundary_io.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;

namespace {

json valid_boundary() { return boundary_to_json(make_random_boundary(3, 4, 1)); }

// Parses and returns the InputError's field (fails the test when nothing is thrown).
std::string field_of_error(const json& doc) {
  try {
    parse_boundary(doc, "test.json");
  } catch (const InputError& e) {
    CHECK(e.file() == "test.json");
    CHECK(!e.reason().empty());
    return e.field();
  }
  FAIL("no InputError for " << doc.dump());
  return {};
}

}  // namespace

TEST_CASE("parse_boundary: a written boundary reads back exactly", "[io]") {
  const Boundary b = make_random_boundary(3, 4, 1);
  const json doc = json::parse(boundary_to_json(b).dump());
  const BoundaryFile f = parse_boundary(doc, "test.json");
  CHECK(f.boundary.m == 3);
  CHECK(f.boundary.n == 4);
  CHECK(f.boundary.bottom == b.bottom);
  CHECK(f.boundary.right == b.right);
  CHECK(!f.net);
}

TEST_CASE("parse_boundary: the net form gives its frame and keeps the net", "[io]") {
  const ControlNet net = make_random_net(4, 2, 3);
  const BoundaryFile f = parse_boundary(json{{"net", json::parse(net_to_json(net).dump())}}, "net.json");
  REQUIRE(f.net);
  CHECK(f.net->points == net.points);
  CHECK(f.boundary.m == 4);
  CHECK(f.boundary.n == 2);
  CHECK(f.boundary.top == boundary_of(net).top);
}

TEST_CASE("parse_boundary: a file of another kind is blamed on its type, a net file with a type is still read",
          "[io]") {
  // refit and degree-limit of a triangle said "bottom: missing"
  json doc = valid_boundary();
  doc["type"] = "triangle";
  CHECK(field_of_error(doc) == "type");
  doc["type"] = "bilinear";  // a surface description
  CHECK(field_of_error(doc) == "type");
  doc["type"] = json::array({1, 2});
  CHECK(field_of_error(doc) == "type");
  // a net file whose other fields include a "type" is still a net file (formats.md: other fields
  // of a net file are ignored)
  const ControlNet net = make_random_net(3, 2, 4);
  const BoundaryFile f =
      parse_boundary(json{{"type", "bezier"}, {"net", json::parse(net_to_json(net).dump())}}, "report.json");
  REQUIRE(f.net);
  CHECK(f.net->points == net.points);
}

TEST_CASE("parse_boundary: every bad input names its field", "[io]") {
  json doc = valid_boundary();
  SECTION("missing side") {
    doc.erase("left");
    CHECK(field_of_error(doc) == "left");
  }
  SECTION("top and bottom lengths differ") {
    doc["top"].push_back({0, 0, 0});
    CHECK(field_of_error(doc) == "top");
  }
  SECTION("left and right lengths differ") {
    doc["right"].erase(doc["right"].size() - 1);
    CHECK(field_of_error(doc) == "right");
  }
  SECTION("a point with two coordinates") {
    doc["bottom"][1] = {1, 2};
    CHECK(field_of_error(doc) == "bottom[1]");
  }
  SECTION("a coordinate that is not a number") {
    doc["left"][2][1] = "x";
    CHECK(field_of_error(doc) == "left[2]");
  }
  SECTION("degree disagrees with the lengths") {
    doc["degree"] = {3, 5};
    CHECK(field_of_error(doc) == "degree");
  }
  SECTION("degree below 1") {
    doc["bottom"] = json::array({doc["bottom"][0]});
    doc["top"] = json::array({doc["top"][0]});
    CHECK(field_of_error(doc) == "bottom");
  }
  SECTION("corners disagree") {
    doc["top"][3][2] = doc["top"][3][2].get<double>() + 1e-3;
    CHECK(field_of_error(doc) == "top-right corner");
  }
  SECTION("not an object") { CHECK(field_of_error(json::array({1, 2})) == ""); }
  SECTION("ragged net") {
    json net = net_to_json(make_random_net(2, 2, 4));
    net[1].erase(0);
    CHECK(field_of_error(json{{"net", net}}) == "net[1]");
  }
}

TEST_CASE("parse_boundary: corner tolerance is relative to the bounding box", "[io]") {
  json doc = valid_boundary();
  doc["top"][0][0] = doc["top"][0][0].get<double>() + 1e-12;  // far below 1e-9 of the diagonal
  CHECK_NOTHROW(parse_boundary(doc, "test.json"));
  BoundaryReadOptions strict;
  strict.corner_tolerance = 1e-14;
  CHECK_THROWS_AS(parse_boundary(doc, "test.json", strict), InputError);
}

TEST_CASE("read_boundary_file: missing files and malformed JSON are input errors", "[io]") {
  CHECK_THROWS_AS(read_boundary_file("/nonexistent/boundary.json"), InputError);
  CHECK_THROWS_WITH(read_boundary_file(COONS_DATA_DIR "/README.md"), Catch::Contains("malformed JSON"));
}

TEST_CASE("parse_boundary: the corner check holds at every scale (no underflow at 1e-170)", "[io]") {
  // a corner moved by half the boundary's size: refused at scale 1 and at 1e-170 alike, where
  // norm() of the gap and of the diagonal underflows to 0
  for (const double scale : {1.0, 1e-100, 1e-170, 1e-300}) {
    const Boundary b =
        transformed(make_random_boundary(3, 3, 7), scale * Eigen::Matrix3d::Identity(), Eigen::RowVector3d::Zero());
    json doc = boundary_to_json(b);
    INFO("scale " << scale);
    CHECK_NOTHROW(parse_boundary(doc, "test.json"));
    doc["bottom"][0][0] = doc["bottom"][0][0].get<double>() + 0.5 * scale;
    CHECK(field_of_error(doc) == "bottom-left corner");
    CHECK(bounding_box_diagonal(b) / scale == Approx(bounding_box_diagonal(make_random_boundary(3, 3, 7))));
  }
}
