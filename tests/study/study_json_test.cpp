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

TEST_CASE("bspline_rows_json: rows read back write the same bspline.json and report section", "[study]") {
  BSplineStudyRow row;
  row.file = "wave.json";
  row.name = "wave";
  row.degree_u = 3;
  row.degree_v = 2;
  row.count_u = 8;
  row.count_v = 7;
  row.notes = {{"left", 0, 2}, {"right", 1, 3}};
  row.solver = "cholmod";
  row.thin_plate_coons = 0.1 + 0.2;
  row.thin_plate_laplace = std::numeric_limits<double>::quiet_NaN();  // a failed solve
  AlphaSearchSummary s;
  s.parameter = -0.0865913 + 1e-17;
  s.value = 7.25;
  s.at_bound = true;
  s.scan = {{-0.25, 9.0}, {0.0, HUGE_VAL}};
  AlphaSearchSummary failed;
  failed.status = SearchStatus::kSolverFailed;
  row.searches = {{"thin_plate", s}, {"e3", failed}};
  const std::vector<BSplineStudyRow> rows = {row};

  const nlohmann::json j = bspline_rows_json(rows);
  std::vector<BSplineStudyRow> back;
  append_bspline_rows(nlohmann::json::parse(j.dump()), "record", &back);
  REQUIRE(back.size() == 1);
  CHECK(bspline_rows_json(back) == j);
  CHECK(bspline_study_json(back) == bspline_study_json(rows));
  CHECK(bspline_study_markdown(back) == bspline_study_markdown(rows));
  CHECK(back[0].thin_plate_coons == row.thin_plate_coons);
  CHECK(std::isnan(back[0].thin_plate_laplace));
  CHECK(back[0].searches[0].second.scan.back().second == HUGE_VAL);
  // a malformed row is an input error naming the record and the field
  std::vector<BSplineStudyRow> none;
  nlohmann::json broken = j;
  broken[0].erase("solver");
  CHECK_THROWS_WITH(append_bspline_rows(broken, "record", &none), Catch::StartsWith("record: bspline: malformed"));
}
