// The generated conclusions of the α study (coons/study/study_conclusions.h): a claim appears only
// when the table supports it.
#include "coons/study/study_conclusions.h"

#include <catch2/catch.hpp>

#include "support/fixtures.h"

using namespace coons;
using coons::test::contains;
using coons::test::joined_lines;

namespace {

ShapeEntry shape_with(const std::string& name, std::optional<double> thin_plate_alpha) {
  ShapeEntry s;
  s.boundary.name = name;
  ShapeOptimum o;
  o.objective = "thin_plate";
  o.alpha.parameter = thin_plate_alpha;
  o.alpha.flat = !thin_plate_alpha;
  s.optima.push_back(o);
  return s;
}

}  // namespace

TEST_CASE("study_conclusions: no single alpha is claimed only when the optima differ", "[study]") {
  StudyResult differ;
  differ.objectives = {"thin_plate"};
  differ.shapes = {shape_with("a", -0.2), shape_with("b", 0.1), shape_with("c", std::nullopt)};
  const std::string d = joined_lines(study_conclusions(differ));
  INFO(d);
  CHECK(contains(d, "no single α is best"));
  CHECK(contains(d, "from -0.2000 (a) to 0.1000 (b) over 2 shapes"));
  CHECK(contains(d, "1 of 3 shapes are flat for every objective (no α is better than another): c"));
  // the same table with optima that agree: the Farin-Hansford sentence must not appear
  StudyResult agree;
  agree.objectives = {"thin_plate"};
  agree.shapes = {shape_with("a", -0.2), shape_with("b", -0.19)};
  const std::string a = joined_lines(study_conclusions(agree));
  INFO(a);
  CHECK_FALSE(contains(a, "no single α is best"));
  CHECK(contains(a, "agree within 0.0100"));
}

TEST_CASE("study_conclusions: mu* is said to stay put only when it does", "[study]") {
  StudyResult r;
  r.objectives = {"thin_plate"};
  DegreeLawEntry law{"conoid", "thin_plate", {}, {}, std::nullopt};
  for (auto [n, mu] : {std::pair<int, double>{4, 15.4}, {8, 7.58}, {16, 6.0}}) {
    DegreeCell c;
    c.degree = n;
    c.mu.parameter = mu;
    law.cells.push_back(c);
  }
  r.laws.push_back(law);
  const std::string drift = joined_lines(study_conclusions(r));
  INFO(drift);
  CHECK_FALSE(contains(drift, "stays put"));
  CHECK(contains(drift, "conoid, thin_plate: μ* drifts with the degree, 15.4 (n = 4) to 6 (n = 16)"));
  for (auto& c : r.laws[0].cells) c.mu.parameter = 6.0 + 0.01 * c.degree;
  CHECK(contains(joined_lines(study_conclusions(r)), "stays put"));
}

TEST_CASE("study_conclusions: the optima that agree are named with their shapes, an optimum on the bound tagged",
          "[study]") {
  StudyResult r;
  r.objectives = {"thin_plate"};
  r.shapes = {shape_with("a", -0.25), shape_with("b", -0.24)};
  r.shapes[0].optima[0].alpha.at_bound = true;
  const std::string s = joined_lines(study_conclusions(r));
  INFO(s);
  CHECK(contains(s, "agree within 0.0100"));
  CHECK(contains(s, "(α* from -0.2500 (a, on the bound) to -0.2400 (b))"));
}
