// Targets of the α search: a boundary file's "target", its numbers bounded as coordinates are
// (json_file.h: kMaxCoordinate). (The --target specification: tests/cli/search_inputs_test.cpp.)
#include "coons/study/target.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "coons/io/input_error.h"
#include "coons/net/control_net.h"

using namespace coons;
using nlohmann::json;

namespace {

std::string file_error(const std::string& text) {
  try {
    (void)target_from_json(json::parse(text), "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

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
}
