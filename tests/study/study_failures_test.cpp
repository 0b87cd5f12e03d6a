// What failed in a study (coons/study/study_failures.h): every kind of failed solve is named, with
// its file; a study where everything succeeded has none.
#include "coons/study/study_failures.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/fixtures.h"

using namespace coons;
using coons::test::contains;

namespace {

AlphaSearchSummary found(double parameter) {
  AlphaSearchSummary s;
  s.parameter = parameter;
  s.value = 1;
  return s;
}

AlphaSearchSummary with_status(SearchStatus status) {
  AlphaSearchSummary s;
  s.status = status;
  return s;
}

ShapeEntry good_shape(const std::string& name) {
  ShapeEntry shape;
  shape.file = name + ".json";
  shape.boundary.name = name;
  ShapeOptimum o;
  o.objective = "thin_plate";
  o.alpha = found(-0.1);
  o.mu = found(12);
  o.coons = 2;
  o.laplace = 3;
  shape.optima.push_back(o);
  shape.curves.resize(3);
  for (SweepRow& row : shape.curves) row.summary.status = solvers::SolveStatus::kSuccess;
  return shape;
}

}  // namespace

TEST_CASE("shape_failures: a failed region, a failed solve at alpha = -1/4 and failed curve rows are named",
          "[study]") {
  ShapeEntry shape = good_shape("wave");
  CHECK(shape_failures(shape).empty());
  shape.optima[0].mu = with_status(SearchStatus::kFailedRegion);
  shape.optima[0].coons = std::numeric_limits<double>::quiet_NaN();
  shape.curves[1].summary.status = solvers::SolveStatus::kDiverged;
  const std::vector<std::string> f = shape_failures(shape);
  REQUIRE(f.size() == 3);
  CHECK(f[0] == "thin_plate: μ* failed_region");
  CHECK(f[1] == "thin_plate: the solve at α = −1/4 failed");
  CHECK(f[2] == "1 of 3 energy-curve solves failed");
  // a weight search that failed, and a search the backend could not run
  ShapeEntry weighted = good_shape("ribbons");
  weighted.optima[0].weight = with_status(SearchStatus::kSolverFailed);
  weighted.optima[0].alpha = with_status(SearchStatus::kNotApplicable);
  CHECK(shape_failures(weighted).size() == 2);
  // flat and not-converged searches are verdicts, not failed solves
  ShapeEntry flat = good_shape("plane");
  flat.optima[0].alpha = with_status(SearchStatus::kFlat);
  flat.optima[0].mu = with_status(SearchStatus::kNotConverged);
  CHECK(shape_failures(flat).empty());
}

TEST_CASE("study_failures: degree cells, reference rows and triangle cells are named with their file", "[study]") {
  StudyResult r;
  r.shapes = {good_shape("dome"), good_shape("saddle")};
  CHECK(study_failures(r).empty());
  DegreeLawEntry law{"saddle", "e3", {}, {}, std::nullopt};
  law.cells.push_back({8, found(-0.2), with_status(SearchStatus::kSolverFailed)});
  r.laws.push_back(law);
  ReferenceTable table{"dome", 3, 3, {}, found(-0.2), 1};
  const double failed = std::numeric_limits<double>::quiet_NaN();
  table.rows = {{-0.25, failed, failed, failed, failed}, {0, 1, 2, 3, 4}};
  r.references.push_back(table);
  TriStudyEntry triangle;
  triangle.file = "bulge.json";
  triangle.boundary.name = "bulge";
  TriStudyCell cell;
  cell.degree = 5;
  cell.c = with_status(SearchStatus::kFailedRegion);
  cell.quadratic = 1;
  cell.laplace = failed;
  triangle.rows.push_back({"twist", {cell}});
  r.triangles.push_back(triangle);
  const std::vector<StudyFailure> f = study_failures(r);
  REQUIRE(f.size() == 4);
  CHECK(f[0].file == "saddle.json");
  CHECK(contains(f[0].what, "saddle: e3 at degree 8: μ* solver_failed"));
  CHECK(f[1].file == "dome.json");
  CHECK(contains(f[1].what, "the reference row at α = -0.25 failed"));
  CHECK(f[2].file == "bulge.json");
  CHECK(contains(f[2].what, "bulge: twist at degree 5: c* failed_region"));
  CHECK(contains(f[3].what, "the solve at c = 0 failed"));
}

TEST_CASE("bspline_study_failures: a failed net energy and a failed search are named", "[study]") {
  BSplineStudyRow row;
  row.file = "wave.json";
  row.name = "wave";
  row.thin_plate_coons = 1;
  row.thin_plate_laplace = 2;
  row.searches = {{"thin_plate", found(-0.1)}};
  CHECK(bspline_study_failures({row}).empty());
  row.thin_plate_laplace = std::numeric_limits<double>::quiet_NaN();
  row.searches.emplace_back("e3", with_status(SearchStatus::kSolverFailed));
  const std::vector<StudyFailure> f = bspline_study_failures({row});
  REQUIRE(f.size() == 2);
  CHECK(f[0].file == "wave.json");
  CHECK(contains(f[1].what, "e3: best α solver_failed"));
}

TEST_CASE("family_failures: a cell's failed searches and failed grid evaluations are named with the family",
          "[study]") {
  AlphaFamilyResult r;
  r.options.count = 4;
  AlphaFamilyCell cell;
  cell.degree = 5;
  cell.objective = "e3";
  cell.alpha_star.resize(4);
  r.cells = {cell, cell};
  CHECK(family_failures(r).empty());
  r.cells[0].failed = 2;
  r.cells[1].objective = "thin_plate";
  r.cells[1].grid_failed = 3;
  const std::vector<StudyFailure> f = family_failures(r);
  REQUIRE(f.size() == 2);
  CHECK(f[0].file.empty());
  CHECK(f[0].what == "random-smooth: e3 at degree 5: 2 of 4 α* searches failed");
  CHECK(f[1].what == "random-smooth: thin_plate at degree 5: 3 evaluations on the best-single-α grid failed");
  r.options.base_name = "dome";
  CHECK(contains(family_failures(r)[0].what, "perturbed:dome: e3 at degree 5"));
}
