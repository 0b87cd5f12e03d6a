// Surface descriptions (docs/formats.md): every type parses; every kind of bad input is an InputError
// that names the field.
#include "coons/io/surface_io.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "coons/io/input_error.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;
using V = Eigen::RowVector3d;

namespace {

const json kSquare = json::array({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
const json kDu = json::array({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
const json kDv = json::array({{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}});
const json kZero4 = json::array({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});

json segment(std::vector<double> a, std::vector<double> b) { return {{"bezier", {a, b}}}; }

json coons_doc(const std::string& type) {
  return {{"type", type},
          {"bottom", segment({0, 0, 0}, {1, 0, 0})},
          {"top", {{"expr", {"t", "1", "2*t"}}}},
          {"left", segment({0, 0, 0}, {0, 1, 0})},
          {"right", {{"expr", {"1", "v", "2*v"}}}}};
}

// The flat square with the cross derivatives of z = 2uv: compatible.
json general_doc() {
  json d = coons_doc("general-coons");
  d["du_left"] = {{"expr", {"1", "0", "2*t"}}};
  d["du_right"] = {{"expr", {"1", "0", "2*t"}}};
  d["dv_bottom"] = {{"expr", {"0", "1", "2*t"}}};
  d["dv_top"] = {{"expr", {"0", "1", "2*t"}}};
  d["twist"] = json::array({{0, 0, 2}, {0, 0, 2}, {0, 0, 2}, {0, 0, 2}});
  return d;
}

// The InputError of parsing doc: its field and reason.
std::pair<std::string, std::string> error_of(const json& doc) {
  try {
    parse_surface(doc, "spec.json");
  } catch (const InputError& e) {
    CHECK(e.file() == "spec.json");
    return {e.field(), e.reason()};
  }
  FAIL("no InputError for " << doc.dump());
  return {};
}

}  // namespace

TEST_CASE("parse_surface: every type of docs/formats.md (and the extensions) builds its surface", "[surfaces]") {
  const std::vector<json> docs = {
      {{"type", "ruled"},
       {"curves", {segment({0, 0, 0}, {1, 0, 0}), {{"expr", {"t", "1", "t^2"}}, {"interval", {0, 1}}}}}},
      {{"type", "sectorial"}, {"curve", segment({0, 0, 0}, {1, 0, 0})}, {"point", {0, 1, 1}}},
      {{"type", "bilinear"}, {"corners", kSquare}},
      {{"type", "conoid"},
       {"directrix", {{"expr", {"t", "0", "1-t^2"}}, {"interval", {-1, 1}}}},
       {"line", {{0, 2, 0}, {1, 0, 0}}},
       {"plane_normal", {1, 0, 0}}},
      coons_doc("bilinear-coons"),
      coons_doc("hermite-coons"),
      {{"type", "ferguson"}, {"corners", kSquare}, {"du", kDu}, {"dv", kDv}},
      {{"type", "hermite16"}, {"corners", kSquare}, {"du", kDu}, {"dv", kDv}, {"twist", kZero4}},
      general_doc(),
      {{"type", "bezier"}, {"net", {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 1}}}}},
      {{"type", "ruled"},
       {"name", "extensions"},
       {"comment", "point and hermite curves"},
       {"curves", {{{"point", {0, 0, 1}}}, {{"hermite", {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}}}}}}},
  };
  for (const json& d : docs) {
    INFO(d.dump());
    const SurfaceFile f = parse_surface(d, "spec.json");
    CHECK(to_string(f.surface.type()) == d["type"].get<std::string>());
    CHECK(f.surface.at(0.5, 0.5).allFinite());
  }
  // The name defaults to the file's stem.
  CHECK(parse_surface(docs[0], "dir/my_surface.json").name == "my_surface");
  // z = 2uv through the general Coons patch.
  const SurfaceFile g = parse_surface(general_doc(), "g.json");
  CHECK((g.surface.at(0.3, 0.6) - V(0.3, 0.6, 0.36)).norm() < 1e-12);
  CHECK(g.conditions.size() == 20);
}

TEST_CASE("parse_surface: wrong counts name the field", "[surfaces]") {
  json d = {{"type", "bilinear"}, {"corners", json::array({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}};
  auto [field, reason] = error_of(d);
  CHECK(field == "corners");
  CHECK(reason.find("exactly 4") != std::string::npos);

  d = {{"type", "ruled"}, {"curves", {segment({0, 0, 0}, {1, 0, 0})}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "curves");

  d = {{"type", "ferguson"},
       {"corners", kSquare},
       {"du", kDu},
       {"dv", json::array({{0, 1, 0}, {0, 1}, {0, 1, 0}, {0, 1, 0}})}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "dv[1]");
  CHECK(reason.find("3 coordinates") != std::string::npos);

  d = coons_doc("bilinear-coons");
  d["top"] = {{"expr", {"t", "1"}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "top.expr");

  d = {{"type", "bezier"}, {"net", {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}}}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "net[1]");
}

TEST_CASE("parse_surface: unknown type, missing and unknown fields", "[surfaces]") {
  auto [field, reason] = error_of({{"type", "nurbs"}, {"corners", kSquare}});
  CHECK(field == "type");
  CHECK(reason.find("unknown type 'nurbs'") != std::string::npos);
  CHECK(reason.find("general-coons") != std::string::npos);

  std::tie(field, reason) = error_of({{"corners", kSquare}});
  CHECK(field == "type");
  CHECK(reason.find("missing") != std::string::npos);

  json d = coons_doc("hermite-coons");
  d.erase("left");
  std::tie(field, reason) = error_of(d);
  CHECK(field == "left");
  CHECK(reason == "missing");

  d = coons_doc("hermite-coons");
  d["twist"] = kZero4;  // not a field of hermite-coons
  std::tie(field, reason) = error_of(d);
  CHECK(field == "twist");

  d = coons_doc("hermite-coons");
  d["bottom"]["degree"] = 3;
  std::tie(field, reason) = error_of(d);
  CHECK(field == "bottom.degree");

  d = coons_doc("hermite-coons");
  d["bottom"] = {{"bezier", {{0, 0, 0}, {1, 0, 0}}}, {"expr", {"t", "0", "0"}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "bottom");

  d = {{"type", "bilinear"}, {"corners", json::array({{0, 0, 0}, {1, 0, "x"}, {0, 1, 0}, {1, 1, 0}})}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "corners[1]");
}

TEST_CASE("parse_surface: an expression that does not parse, or is not finite, names its component", "[surfaces]") {
  json d = coons_doc("bilinear-coons");
  d["top"] = {{"expr", {"t", "1", "2*t +"}}};
  auto [field, reason] = error_of(d);
  CHECK(field == "top.expr[2]");
  CHECK(reason.find("does not parse") != std::string::npos);

  d["top"] = {{"expr", {"t", "sinh(", "2*t"}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "top.expr[1]");

  d["top"] = {{"expr", {"w", "1", "2*t"}}};  // unknown variable
  std::tie(field, reason) = error_of(d);
  CHECK(field == "top.expr[0]");

  d = {{"type", "ruled"}, {"curves", {segment({0, 0, 0}, {1, 0, 0}), {{"expr", {"t", "1", "sqrt(t - 0.5)"}}}}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "curves[1].expr[2]");
  CHECK(reason.find("at t = 0 is not finite") != std::string::npos);

  d = {{"type", "ruled"},
       {"curves", {segment({0, 0, 0}, {1, 0, 0}), {{"expr", {"t", "1", "t"}}, {"interval", {2, 2}}}}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "curves[1].interval");

  // a width beyond a double made every t NaN, and the error blamed expr[0] "at t = -nan"
  d = {{"type", "ruled"},
       {"curves", {segment({0, 0, 0}, {1, 0, 0}), {{"expr", {"0", "1", "0"}}, {"interval", {-1e308, 1e308}}}}}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "curves[1].interval");
  CHECK(reason.find("overflows") != std::string::npos);
}

TEST_CASE("parse_surface: corners that disagree name the corner, the condition and the gap", "[surfaces]") {
  json d = coons_doc("bilinear-coons");
  d["right"] = {{"expr", {"1", "v", "2*v + 0.01"}}};  // right(0) = (1,0,0.01) ≠ bottom(1)
  auto [field, reason] = error_of(d);
  CHECK(field == "right");
  CHECK(reason.find("bottom-right") != std::string::npos);
  CHECK(reason.find("right(0) = bottom(1)") != std::string::npos);
  CHECK(reason.find("0.01") != std::string::npos);
}

TEST_CASE("parse_surface: incompatible general-Coons data name the corner and the condition", "[surfaces]") {
  json d = general_doc();
  d["twist"][2] = {0, 0, 2.5};  // r_uv(0, 1) must be 2
  auto [field, reason] = error_of(d);
  CHECK(field == "twist[2]");
  CHECK(reason.find("top-left") != std::string::npos);
  CHECK(reason.find("twist[2] = du_left'(1)") != std::string::npos);
  CHECK(reason.find("0.5") != std::string::npos);

  d = general_doc();
  d["dv_top"] = {{"expr", {"0", "1", "2*t + 0.1"}}};  // dv_top(0) = (0,1,0.1) but left'(1) = (0,1,0)
  std::tie(field, reason) = error_of(d);
  CHECK(field == "dv_top");
  CHECK(reason.find("top-left") != std::string::npos);
  CHECK(reason.find("dv_top(0) = left'(1)") != std::string::npos);

  // A looser tolerance accepts it.
  SurfaceReadOptions loose;
  loose.derivative_tolerance = 0.2;
  CHECK_NOTHROW(parse_surface(d, "spec.json", loose));
}

TEST_CASE("parse_surface: far from the origin the tolerance of tangents grows by the numerical derivative's error",
          "[surfaces]") {
  // The pillow of LN1 (flat unit square, cross derivatives and twists of sin(pi u) sin(pi v)) at
  // x = 1e8: the tangents of its expression sides are good to about 1e-5 there, and the exact data
  // were refused "by 1.18e-05 (tolerance 1.41e-07)".
  const auto pillow = [](const std::string& x0, double du) {
    json d = {{"type", "general-coons"},
              {"bottom", {{"expr", {x0 + "+t", "0", "0"}}}},
              {"top", {{"expr", {x0 + "+t", "1", "0"}}}},
              {"left", {{"expr", {x0, "t", "0"}}}},
              {"right", {{"expr", {x0 + "+1", "t", "0"}}}},
              {"du_left", {{"expr", {fmt::format("{}", du), "0", "pi*sin(pi*t)"}}}},
              {"du_right", {{"expr", {"1", "0", "-pi*sin(pi*t)"}}}},
              {"dv_bottom", {{"expr", {"0", "1", "pi*sin(pi*t)"}}}},
              {"dv_top", {{"expr", {"0", "1", "-pi*sin(pi*t)"}}}}};
    const double pi2 = M_PI * M_PI;
    d["twist"] = json::array({{0, 0, pi2}, {0, 0, -pi2}, {0, 0, -pi2}, {0, 0, pi2}});
    return d;
  };
  for (const char* x0 : {"0", "1e6", "1e8"}) {
    INFO("x0 = " << x0);
    CHECK_NOTHROW(parse_surface(pillow(x0, 1), "spec.json"));
    // a cross derivative that is wrong by far more than that is still refused, the bound named
    const auto [field, reason] = error_of(pillow(x0, 1.01));
    CHECK(field == "du_left");
    CHECK(reason.find("du_left(0) = bottom'(0) fails by 0.01") != std::string::npos);
    CHECK(reason.find("the numerical derivative's error bound") != std::string::npos);
  }
}

TEST_CASE("parse_surface: a conoid whose line is parallel to its plane is rejected", "[surfaces]") {
  json d = {{"type", "conoid"},
            {"directrix", segment({0, 0, 1}, {1, 0, 1})},
            {"line", {{0, 1, 0}, {0, 1, 0}}},
            {"plane_normal", {1, 0, 0}}};
  auto [field, reason] = error_of(d);
  CHECK(field == "plane_normal");
  CHECK(reason.find("parallel") != std::string::npos);
  d["line"] = {{0, 1, 0}, {0, 0, 0}};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "line[1]");
  CHECK(reason == "the line's direction is the zero vector");
  d["line"] = {{0, 1, 0}, {0, 1, 0}};
  d["plane_normal"] = {0, 0, 0};
  std::tie(field, reason) = error_of(d);
  CHECK(field == "plane_normal");
  CHECK(reason == "the plane's normal is the zero vector");
}

TEST_CASE("parse_surface: a conoid's tiny direction and normal are the same conoid as ordinary ones", "[surfaces]") {
  // norm() and n·d of [1e-200, 0, 0] underflow to 0: such a line was refused, or called parallel,
  // though the conoid depends on the two vectors only through ratios
  auto spec = [](double d, double n) {
    return json{{"type", "conoid"},
                {"directrix", segment({0, 0, 1}, {1, 0.5, 1})},
                {"line", {{0, 1, 0}, {d, 0, 0.25 * d}}},
                {"plane_normal", {n, 0, 0}}};
  };
  const Surface ordinary = parse_surface(spec(1, 1), "spec.json").surface;
  for (const auto& [d, n] : {std::pair{1e-200, 1.0}, {1.0, 1e-320}, {1e-300, 1e-300}}) {
    INFO(d << " " << n);
    const Surface tiny = parse_surface(spec(d, n), "spec.json").surface;
    for (const double u : {0.0, 0.3, 1.0})
      for (const double v : {0.0, 0.6, 1.0}) CHECK((tiny.at(u, v) - ordinary.at(u, v)).norm() <= 1e-15);
  }
}

TEST_CASE("read_surface_file: unreadable files and malformed JSON", "[surfaces]") {
  CHECK_THROWS_AS(read_surface_file("/nonexistent/spec.json"), InputError);
}
