// study_part_json / append_study_part: the per-shape study's result survives the trip through
// JSON exactly (the record of a sharded boundary-file study), non-finite numbers included.
#include "coons/study/study_json.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The study of one smooth boundary at degrees 3 and 4 (5 curve points).
StudyResult smooth_study_result() {
  StudyInput in;
  in.file = "smooth.json";
  in.boundary = make_smooth_boundary(3, 3, 7);
  in.boundary.name = "smooth";
  in.one_ring = "one data ring";
  StudyOptions options;
  options.degrees = {3, 4};
  options.curve_points = 5;
  return run_study({in}, options);
}

}  // namespace

TEST_CASE("study_part_json: a study result read back writes the same JSON and results", "[study]") {
  StudyResult result = smooth_study_result();
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

TEST_CASE("append_study_part: an integer field holding a float beyond int is refused not converted", "[study]") {
  // get<int> of 1e300 is undefined behaviour: every integer of a part is read as json_integer
  StudyResult result = smooth_study_result();
  TriStudyEntry triangle;  // a triangle's entry (no search run: only its integers matter here)
  triangle.boundary.n = 3;
  for (auto& side : triangle.boundary.sides) side = Eigen::MatrixX3d::Zero(4, 3);  // n + 1 points each
  TriStudyCell cell;
  cell.degree = 3;
  triangle.rows.push_back({"thin_plate", {cell}});
  result.triangles.push_back(triangle);
  if (result.fit_deviations.empty()) result.fit_deviations.push_back({"smooth", {{3, 0.1}}});  // elevated, not refitted
  if (result.references.empty()) result.references.push_back({"smooth", 3, 3, {}, {}, 0});     // no target given
  const nlohmann::json part = nlohmann::json::parse(study_part_json(result).dump());
  for (const char* at : {"/shapes/0/boundary/m", "/shapes/0/boundary/n", "/shapes/0/optima/0/alpha/local_minima",
                         "/shapes/0/optima/0/alpha/evaluations", "/shapes/0/optima/0/alpha/solves",
                         "/shapes/0/optima/0/alpha/failed_evaluations", "/shapes/0/curves/0/summary/iterations",
                         "/shapes/0/curves/0/summary/factor_nnz", "/shapes/0/pictures/0/m", "/shapes/0/pictures/0/n",
                         "/laws/0/cells/0/degree", "/fit_deviations/0/max_deviation/0/0", "/references/0/m",
                         "/references/0/n", "/triangles/0/boundary/n", "/triangles/0/rows/0/cells/0/degree"})
    for (const double bad : {1e300, -1e300, 1e10, 2.5}) {
      INFO(at << " = " << bad);
      nlohmann::json edited = part;
      const nlohmann::json::json_pointer pointer(at);
      REQUIRE(edited.contains(pointer));
      edited[pointer] = bad;
      StudyResult into;
      CHECK_THROWS_WITH(
          append_study_part(edited, "shard-0-of-1.jsonl", &into),
          Catch::StartsWith("shard-0-of-1.jsonl: result: malformed: ") && Catch::Contains("must be an integer"));
    }
  // a picture of degree INT_MAX: its point count is computed without overflow, and does not match
  nlohmann::json edited = part;
  edited["/shapes/0/pictures/0/m"_json_pointer] = 2147483647;
  StudyResult into;
  CHECK_THROWS_WITH(append_study_part(edited, "shard-0-of-1.jsonl", &into),
                    Catch::Contains("a picture's net has the wrong number of points"));
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
  s.at_bound = false;  // (interior: on a bound the merge would refuse it)
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
  // an integer holding a float beyond int (get<int> of it is undefined behaviour) is malformed too
  for (const char* at : {"/0/degrees/0", "/0/degrees/1", "/0/counts/0", "/0/counts/1", "/0/notes/0/1", "/0/notes/0/2",
                         "/0/searches/0/1/evaluations"}) {
    INFO(at);
    broken = nlohmann::json::parse(j.dump());
    const nlohmann::json::json_pointer pointer(at);
    REQUIRE(broken.contains(pointer));
    broken[pointer] = 1e300;
    CHECK_THROWS_WITH(append_bspline_rows(broken, "record", &none),
                      Catch::StartsWith("record: bspline: malformed: ") && Catch::Contains("must be an integer"));
  }
}
