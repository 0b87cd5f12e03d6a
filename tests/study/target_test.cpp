// Targets of the α search: --target specifications and a boundary file's "target", their numbers
// bounded as coordinates are (json_file.h: kMaxCoordinate).
#include "coons/study/target.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "coons/io/input_error.h"
#include "coons/net/control_net.h"

using namespace coons;
using nlohmann::json;

namespace {

// The message of the InputError that resolving `spec` throws ("" when it does not throw).
std::string spec_error(const std::string& spec) {
  try {
    (void)resolve_target(spec, "b.json", Boundary{}, 41);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string file_error(const std::string& text) {
  try {
    (void)target_from_json(json::parse(text), "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("resolve_target: numbers beyond the coordinate bound are bad input naming --target", "[study]") {
  for (const std::string spec :
       {"sphere:0,0,0,1e200", "sphere:1e61,0,0,1", "plane:0,0,0,0,0,1e200", "cylinder:0,0,0,0,0,1,-1e200"}) {
    INFO(spec);
    CHECK(spec_error(spec).rfind("command line: --target: '", 0) == 0);
    CHECK(spec_error(spec).find("beyond the bound |x| <= 1e+60") != std::string::npos);
  }
  CHECK(spec_error("sphere:0,0,0,1e60").empty());
}

TEST_CASE("resolve_target: a subnormal value is a finite number, one below the doubles is refused", "[study]") {
  CHECK(spec_error("sphere:0,0,0,1e-320").empty());
  CHECK(resolve_target("sphere:0,0,0,1e-320", "b.json", Boundary{}, 41)->radius == 1e-320);
  // 1e-400 was read as 0, as every number of the command line was (the options now refuse it too)
  CHECK(spec_error("sphere:1e-400,0,0,1").find("'1e-400' is below the smallest double and would be read as 0") !=
        std::string::npos);
  CHECK(resolve_target("sphere:0.0e-5,-0,0,1", "b.json", Boundary{}, 41)->point.x() == 0);
  // what stod also refused stays refused
  for (const std::string spec : {"sphere:0,0,0,1e999", "sphere:0,0,0,x", "sphere:0,0,,1", "sphere:0,0,0,1 "})
    CHECK(spec_error(spec).find("is not a finite number") != std::string::npos);
}

TEST_CASE("target_from_json: numbers beyond the coordinate bound are bad input naming the field", "[study]") {
  const std::string radius = file_error(R"({"target": {"sphere": {"center": [0, 0, 0], "radius": 1e200}}})");
  CHECK(radius.rfind("t.json: target.sphere.radius: the radius is ", 0) == 0);
  CHECK(radius.find("e+199, beyond the bound |x| <= 1e+60") != std::string::npos);
  const std::string centre = file_error(R"({"target": {"sphere": {"center": [0, 1e200, 0], "radius": 1}}})");
  CHECK(centre.rfind("t.json: target.sphere.center: coordinate 1 is ", 0) == 0);
  CHECK(centre.find("e+199, beyond the bound |x| <= 1e+60") != std::string::npos);
  CHECK(file_error(R"({"target": {"plane": {"point": [0, 0, 0], "normal": [0, 0, 1e200]}}})")
            .rfind("t.json: target.plane.normal: coordinate 2", 0) == 0);
  CHECK(file_error(R"({"target": {"sphere": {"center": [0, 0, 0], "radius": 1e-320}}})").empty());
}

TEST_CASE("target_from_json: a zero axis or normal is refused naming it, and a tiny one is a direction", "[study]") {
  const std::string reason = "axis/normal must not be the zero vector";
  CHECK(file_error(R"({"target": {"plane": {"point": [0, 0, 0], "normal": [0, 0, 0]}}})") ==
        "t.json: target.plane.normal: " + reason);
  CHECK(file_error(R"({"target": {"cylinder": {"point": [0, 0, 0], "axis": [0, -0.0, 0], "radius": 1}}})") ==
        "t.json: target.cylinder.axis: " + reason);
  CHECK(spec_error("plane:0,0,0,0,0,0") == "command line: --target: " + reason);
  CHECK(spec_error("cylinder:0,0,0,0,0,1,0") == "command line: --target: radius must be positive");
  // 1e-161 came out 1.006 long from normalized() (its squared norm is subnormal), 1e-320 was
  // refused: both are directions, held scaled by a power of two
  const auto file_normal = [](const char* normal) {
    return target_from_json(
               json::parse(std::string(R"({"target": {"plane": {"point": [0, 0, 0], "normal": )") + normal + "}}}"),
               "t.json")
        ->direction;
  };
  CHECK(file_normal("[1e-161, 0, 0]").normalized() == Eigen::RowVector3d(1, 0, 0));
  CHECK(file_normal("[1e-320, 0, 0]").normalized() == Eigen::RowVector3d(1, 0, 0));
  CHECK(file_normal("[0, 3e-200, -6e-200]").normalized().norm() == Approx(1).epsilon(1e-15));
  CHECK(file_normal("[0, 3, -6]") == Eigen::RowVector3d(0, 0.75, -1.5));  // by 2^-2, exactly
  CHECK(resolve_target("cylinder:0,0,0,1e-320,0,0,1", "b.json", Boundary{}, 41)->direction.normalized() ==
        Eigen::RowVector3d(1, 0, 0));
}
