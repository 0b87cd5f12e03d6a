// study_part_json / append_study_part: the per-shape study's result survives the trip through
// JSON exactly (the record of a sharded boundary-file study), non-finite numbers included.
#include "coons/study/study_json.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("study_part_json: a study result read back writes the same JSON and results", "[study]") {
  StudyInput in;
  in.file = "smooth.json";
  in.boundary = make_smooth_boundary(3, 3, 7);
  in.boundary.name = "smooth";
  in.one_ring = "one data ring";
  StudyOptions options;
  options.degrees = {3, 4};
  options.curve_points = 5;
  StudyResult result = run_study({in}, options);
  REQUIRE(result.shapes.size() == 1);
  REQUIRE_FALSE(result.shapes[0].curves.empty());
  // a value no JSON number holds, and an odd one: both must come back bit for bit
  result.shapes[0].optima[0].alpha.scan.emplace_back(0.125, HUGE_VAL);
  result.shapes[0].optima[0].coons = 0.1 + 0.2;

  const nlohmann::json part = study_part_json(result);
  StudyResult back;
  back.degrees = result.degrees;
  back.objectives = result.objectives;
  append_study_part(nlohmann::json::parse(part.dump()), "record", &back);
  CHECK(study_part_json(back) == part);
  CHECK(study_results_json(back) == study_results_json(result));
  CHECK(back.shapes[0].optima[0].alpha.scan.back().second == HUGE_VAL);
  CHECK(back.shapes[0].optima[0].coons == result.shapes[0].optima[0].coons);
  CHECK(back.shapes[0].pictures.size() == result.shapes[0].pictures.size());
  CHECK(max_difference(back.shapes[0].pictures[0].second, result.shapes[0].pictures[0].second) == 0);
}

TEST_CASE("append_study_part: a malformed part is an input error naming the record", "[study]") {
  StudyResult into;
  nlohmann::json part = {{"shapes", nlohmann::json::array({{{"file", 3}}})},
                         {"laws", nlohmann::json::array()},
                         {"fit_deviations", nlohmann::json::array()},
                         {"references", nlohmann::json::array()},
                         {"triangles", nlohmann::json::array()}};
  CHECK_THROWS_WITH(append_study_part(part, "shard-0-of-1.jsonl", &into),
                    Catch::Matchers::StartsWith("shard-0-of-1.jsonl: result: malformed"));
}
