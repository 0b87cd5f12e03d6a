// The input edge's limits: nesting depth, file size, integer ranges and coordinate magnitudes are
// checked when a file is read, and each refusal is an InputError naming file, field and reason.
#include "coons/io/json_file.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "coons/io/surface_io.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;

namespace {

std::string nested_arrays(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// The InputError thrown by `read`, or a failed test when nothing is thrown.
template <typename Read>
InputError error_of(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return InputError("", "", "");
}

}  // namespace

TEST_CASE("read_json_file: a 100,000-level nested target is refused, not recursed into", "[io]") {
  const TempDir dir;
  json doc = boundary_to_json(make_random_boundary(3, 3, 1));
  std::string text = doc.dump();
  text.pop_back();  // the closing brace
  text += ", \"target\": " + nested_arrays(100000) + "}";
  const std::string path = dir.write("deep.json", text);
  const InputError e = error_of([&] { read_boundary_file(path); });
  CHECK(e.file() == path);
  CHECK(e.field() == "(document)");
  CHECK(e.reason() == "nesting deeper than 64 levels");
  CHECK(std::string(e.what()) == path + ": (document): nesting deeper than 64 levels");
}

TEST_CASE("parse_json_text: the depth limit counts containers, the top level being the first", "[io]") {
  CHECK_NOTHROW(parse_json_text(nested_arrays(64), "t.json"));
  CHECK_THROWS_WITH(parse_json_text(nested_arrays(65), "t.json"), "t.json: (document): nesting deeper than 64 levels");
  JsonReadOptions shallow;
  shallow.max_depth = 3;
  CHECK_NOTHROW(parse_json_text(R"({"a": {"b": [1]}})", "t.json", shallow));
  CHECK_THROWS_WITH(parse_json_text(R"({"a": {"b": [[1]]}})", "t.json", shallow),
                    "t.json: (document): nesting deeper than 3 levels");
}

TEST_CASE("parse_json_text: a number beyond the doubles names its field and the number", "[io]") {
  // it was "(document): unreadable JSON ([json.exception.out_of_range.406] number overflow parsing '1e400')"
  CHECK_THROWS_WITH(parse_json_text(R"({"bottom": [[1e400, 0, 0], [1, 0, 0]]})", "t.json"),
                    "t.json: bottom[0][0]: the number '1e400' is beyond the range of doubles");
  CHECK_THROWS_WITH(parse_json_text(R"({"bottom": [[0, 0, 0], [1, 0, -1e999]]})", "t.json"),
                    "t.json: bottom[1][2]: the number '-1e999' is beyond the range of doubles");
  CHECK_THROWS_WITH(parse_json_text(R"({"name": "x", "ribbons": {"left": 2e308}})", "t.json"),
                    "t.json: ribbons.left: the number '2e308' is beyond the range of doubles");
  CHECK_THROWS_WITH(parse_json_text("1e999", "t.json"),
                    "t.json: (document): the number '1e999' is beyond the range of doubles");
}

TEST_CASE("parse_json_text: a number below the smallest double names its field, zeros and subnormals do not", "[io]") {
  // 1e-5000 was read as 0 without a word (the command line and Matrix Market refuse it)
  const std::string reason =
      "a number below the smallest double, which would be read as 0 (write 0, or a value of at least about 5e-324)";
  CHECK_THROWS_WITH(parse_json_text(R"({"bottom": [[0, 0, 0], [1, 0, 1e-5000]]})", "t.json"),
                    "t.json: bottom[1][2]: " + reason);
  CHECK_THROWS_WITH(parse_json_text(R"({"a": [0.5, -0.0, 0e7], "b": {"c": -2.5e-400}})", "t.json"),
                    "t.json: b.c: " + reason);
  // an integer beyond 64 bits is read as a double: the scan counts it as one, so that the next
  // number is checked as itself (it let 1e-5000 pass, or named the number before it)
  CHECK_THROWS_WITH(parse_json_text(R"({"a": 100000000000000000000, "b": [0.0, 1e-5000]})", "t.json"),
                    "t.json: b[1]: " + reason);
  CHECK_THROWS_WITH(parse_json_text(R"({"a": [-9223372036854775809, 0.0], "b": [0.5, -1e-999]})", "t.json"),
                    "t.json: b[1]: " + reason);
  // zeros in any spelling, subnormals, and such text inside strings are numbers or text as written
  const nlohmann::json ok = parse_json_text(
      R"({"z": [0.0, -0e-5000, 0.000e+12, 1e-320], "s": "1e-5000 \" 2e-999", "i": [0, -0, 12]})", "t.json");
  CHECK(ok["z"][0] == 0.0);
  CHECK(ok["z"][3].get<double>() > 0);
  CHECK(ok["s"] == "1e-5000 \" 2e-999");
}

TEST_CASE("read_json_file: a file above the size limit is refused before it is parsed", "[io]") {
  const TempDir dir;
  const std::string path = dir.write("b.json", boundary_to_json(make_random_boundary(3, 3, 1)).dump());
  JsonReadOptions small;
  small.max_bytes = 100;
  const InputError e = error_of([&] { read_json_file(path, small); });
  CHECK(e.file() == path);
  CHECK(e.field() == "(document)");
  CHECK(contains(e.reason(), "more than the limit of 100 bytes"));
  small.max_bytes = 1 << 20;
  CHECK(read_json_file(path, small).contains("bottom"));
}

TEST_CASE("JsonReadOptions: is_valid refuses zero limits", "[io]") {
  JsonReadOptions o;
  std::string why;
  CHECK(o.is_valid(&why));
  o.max_depth = 0;
  CHECK_FALSE(o.is_valid(&why));
  CHECK(contains(why, "max_depth"));
}

TEST_CASE("parse_boundary: a degree beyond int is refused, not truncated", "[io]") {
  json doc = boundary_to_json(make_random_boundary(3, 3, 1));
  doc["degree"] = json::parse("[4294967299, 4294967299]");
  const InputError e = error_of([&] { parse_boundary(doc, "b.json"); });
  CHECK(e.file() == "b.json");
  CHECK(e.field() == "degree[0]");
  CHECK(e.reason() == "must be an integer in [1, 2147483647], not 4294967299");
  doc["degree"] = json::parse("[3, -18446744073709551615]");  // a float: out of any integer range
  CHECK(error_of([&] { parse_boundary(doc, "b.json"); }).field() == "degree[1]");
  doc["degree"] = json::parse("[3, 0]");
  CHECK(error_of([&] { parse_boundary(doc, "b.json"); }).field() == "degree[1]");
  doc["degree"] = json::parse("[3, 3]");
  CHECK_NOTHROW(parse_boundary(doc, "b.json"));
}

TEST_CASE("json_integer: every integer JSON kind is checked against both bounds", "[io]") {
  CHECK(json_integer(json(5), "f", "k", 1, 10) == 5);
  CHECK(json_integer(json(-3), "f", "k", -5, 10) == -3);
  CHECK_THROWS_WITH(json_integer(json(18446744073709551615ull), "f", "k", 1, 10),
                    "f: k: must be an integer in [1, 10], not 18446744073709551615");
  CHECK_THROWS_WITH(json_integer(json(-6), "f", "k", -5, 10), "f: k: must be an integer in [-5, 10], not -6");
  CHECK_THROWS_WITH(json_integer(json(2.5), "f", "k", 1, 10), "f: k: must be an integer in [1, 10], not 2.5");
  CHECK_THROWS_WITH(json_integer(json("3"), "f", "k", 1, 10), "f: k: must be an integer in [1, 10], not a string");
}

TEST_CASE("parse_boundary: coordinates of 1e308 are refused with the point and the bound", "[io]") {
  json doc = boundary_to_json(make_random_boundary(3, 3, 1));
  doc["bottom"][2][1] = 1e308;
  const InputError e = error_of([&] { parse_boundary(doc, "b.json"); });
  CHECK(e.file() == "b.json");
  CHECK(e.field() == "bottom[2]");
  CHECK(contains(e.reason(), "coordinate 1"));
  CHECK(contains(e.reason(), "1e+60"));
  doc["bottom"][2][1] = -kMaxCoordinate;  // the bound itself is accepted (corners are unaffected)
  CHECK_NOTHROW(parse_boundary(doc, "b.json"));

  const ControlNet net = make_random_net(2, 2, 3);
  json with_net{{"net", net_to_json(net)}};
  with_net["net"][1][2][0] = -1e200;
  CHECK(error_of([&] { parse_boundary(with_net, "n.json"); }).field() == "net[1][2]");
}

TEST_CASE("parse_surface: coordinates and analytic curves beyond the bound are refused", "[io]") {
  const json bilinear = json::parse(R"({"type": "bilinear", "corners": [[0,0,0],[1,0,0],[0,1,0],[1,1,1e308]]})");
  const InputError e = error_of([&] { parse_surface(bilinear, "s.json"); });
  CHECK(e.field() == "corners[3]");
  CHECK(contains(e.reason(), "coordinate 2"));
  CHECK(contains(e.reason(), "1e+60"));

  const json ruled = json::parse(R"({"type": "ruled", "curves": [{"bezier": [[0,0,0],[1,0,0]]},
      {"expr": ["t", "1", "1e200 * t"], "interval": [0, 1]}]})");
  const InputError f = error_of([&] { parse_surface(ruled, "r.json"); });
  CHECK(f.field() == "curves[1].expr[2]");
  CHECK(contains(f.reason(), "beyond the bound"));
}

TEST_CASE("json_integer: an integral float is refused as written, not printed as the integer it equals", "[io]") {
  // "degree": [3.0, 3] must not read "must be an integer in [1, 2147483647], not 3"
  CHECK_THROWS_WITH(json_integer(json::parse("3.0"), "f", "degree[0]", 1, 2147483647),
                    "f: degree[0]: must be an integer in [1, 2147483647], not 3.0 (a float)");
  CHECK_THROWS_WITH(json_integer(json::parse("1e18"), "f", "k", 1, 10),
                    "f: k: must be an integer in [1, 10], not 1e+18 (a float)");
  // beyond 64 bits an integer as written is read as a double: it was called "a float"
  CHECK_THROWS_WITH(json_integer(json::parse("1e300"), "f", "k", 1, 10),
                    "f: k: must be an integer in [1, 10], not 1e+300 (beyond the 64-bit integers)");
  CHECK_THROWS_WITH(json_integer(json::parse("100000000000000000000"), "f", "rings", 1, 10),
                    "f: rings: must be an integer in [1, 10], not 1e+20 (beyond the 64-bit integers)");
  CHECK_THROWS_WITH(json_integer(json::parse("-100000000000000000000"), "f", "rings", 1, 10),
                    "f: rings: must be an integer in [1, 10], not -1e+20 (beyond the 64-bit integers)");
  CHECK_THROWS_WITH(json_integer(json::parse("0.1"), "f", "k", 1, 10), "f: k: must be an integer in [1, 10], not 0.1");
}

TEST_CASE("parse_boundary: with min_model_size a smaller model is refused at its largest point", "[io]") {
  // the searches ask for kMinModelSize: energies scale as s^2, and below about 1e-150 they are
  // subnormal or zero; without it (every other reader) a model of any size is read
  const Boundary b = make_random_boundary(3, 4, 5);
  const auto scaled = [&](double s) {
    Boundary c = b;
    for (Eigen::MatrixX3d* side : {&c.bottom, &c.top, &c.left, &c.right}) *side *= s;
    return boundary_to_json(c);
  };
  BoundaryReadOptions search;
  search.min_model_size = kMinModelSize;
  double largest = 0;
  for (const Eigen::MatrixX3d* side : {&b.bottom, &b.top, &b.left, &b.right})
    largest = std::max(largest, side->cwiseAbs().maxCoeff());
  const InputError e = error_of([&] { parse_boundary(scaled(1e-170), "tiny.json", search); });
  CHECK(e.file() == "tiny.json");
  CHECK(contains(e.reason(), "below 1e-60"));
  CHECK(contains(e.reason(), "scale the model up"));
  CHECK_NOTHROW(parse_boundary(scaled(1e-170), "tiny.json"));
  // the field is the point of largest magnitude
  const json doc = scaled(1e-170);
  const std::string side = e.field().substr(0, e.field().find('['));
  const int k = std::stoi(e.field().substr(e.field().find('[') + 1));
  double at = 0;
  for (const json& c : doc[side][std::size_t(k)]) at = std::max(at, std::abs(c.get<double>()));
  CHECK(at == Approx(largest * 1e-170).epsilon(1e-12));
  // the bound itself is accepted, and so is a model at the origin
  CHECK_NOTHROW(parse_boundary(scaled(kMinModelSize / largest * (1 + 1e-12)), "b.json", search));
  CHECK_THROWS(parse_boundary(scaled(kMinModelSize / largest * (1 - 1e-12)), "b.json", search));
  CHECK_NOTHROW(parse_boundary(scaled(0.0), "zero.json", search));

  const ControlNet net = make_random_net(2, 3, 7);
  json small{{"net", net_to_json(net)}};
  for (json& row : small["net"])
    for (json& point : row)
      for (json& c : point) c = c.get<double>() * 1e-100;
  const InputError n = error_of([&] { parse_boundary(small, "n.json", search); });
  CHECK(n.field().rfind("net[", 0) == 0);
  CHECK(contains(n.reason(), "below 1e-60"));
  CHECK_NOTHROW(parse_boundary(small, "n.json"));
}

TEST_CASE("parse_json_text: a key given twice in one object is bad input naming its path", "[io]") {
  // nlohmann keeps the last copy silently: a boundary with two "net" fields was solved with one
  const auto field_of = [](const std::string& text) -> std::string {
    try {
      parse_json_text(text, "B.json");
    } catch (const InputError& e) {
      return e.field();
    }
    return "(accepted)";
  };
  CHECK(field_of(R"({"net": [[1]], "name": "a", "net": [[2]]})") == "net");
  CHECK(field_of(R"({"ribbons": {"left": [], "top": [], "left": []}})") == "ribbons.left");
  CHECK(field_of(R"({"sides": [{"a": 1}, [0, {"b": 1, "b": 2}]]})") == "sides[1][1].b");
  CHECK(field_of(R"([{"x": 1}, {"x": 1, "x": 1}])") == "[1].x");
  // the same key in different objects, or a value equal to a key, is fine
  CHECK(field_of(R"({"a": {"a": 1}, "b": [{"a": 1}, {"a": "a"}], "c": "a"})") == "(accepted)");
}
