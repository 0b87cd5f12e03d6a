#include "coons/study/tri_study.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "coons/config.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/study/tri_search.h"
#include "coons/tri/tri_solve.h"
#include "tri/tri_fixtures.h"

using namespace coons;
using namespace coons::tri;
using namespace coons::tri_test;

namespace {

// A planar triangle (z = 0) with a curved in-plane boundary and the plane z = 0 as its target:
// every member of the family keeps the net in the plane, so the target objective is flat.
TriStudyInput planar_input(int n) {
  TriNet net = random_tri_net(n, 7);
  net.points.col(2).setZero();
  Target plane;
  plane.kind = Target::Kind::kPlane;
  plane.direction = Eigen::RowVector3d(0, 0, 1);
  plane.samples = 9;
  return {"planar.json", boundary_of(net, "planar"), plane};
}

}  // namespace

TEST_CASE("tri_study_objectives: thin plate, E3, Dirichlet and twist, and target only with a target", "[study][tri]") {
  TriStudyInput in = planar_input(4);
  CHECK(tri_study_objectives(in) == std::vector<std::string>{"thin_plate", "e3", "dirichlet", "twist", "target"});
  in.target.reset();
  CHECK(tri_study_objectives(in) == std::vector<std::string>{"thin_plate", "e3", "dirichlet", "twist"});
  for (const std::string& name : tri_study_objectives(planar_input(4))) {
    std::string why;
    INFO(name);
    CHECK(parse_tri_objective(name, &why));
  }
}

TEST_CASE("run_tri_study: the own degree, then every higher study degree, each cell is search_tri_c there",
          "[study][tri]") {
  TriStudyInput in{"random.json", boundary_of(random_tri_net(5, 11), "random"), std::nullopt};
  const std::vector<TriStudyEntry> out = run_tri_study({in}, {3, 4, 5, 7}, &lu());
  REQUIRE(out.size() == 1);
  CHECK(out[0].solver == "eigen-lu");
  CHECK_FALSE(out[0].solver_picked_automatically);
  REQUIRE(out[0].rows.size() == 4);
  for (const TriStudyRow& row : out[0].rows) {
    INFO(row.objective);
    REQUIRE(row.cells.size() == 2);  // degree 5 (its own) and 7; 3, 4 and a repeated 5 are left out
    CHECK(row.cells[0].degree == 5);
    CHECK(row.cells[1].degree == 7);
    // the degree-7 cell is the search on the exactly elevated boundary
    const TriNet elevated = elevate_degree(frame_net(in.boundary), 2);
    std::string why;
    const TriObjective objective = *parse_tri_objective(row.objective, &why);
    AlphaSearchOptions options;
    std::tie(options.lower, options.upper) = default_tri_bounds(7);
    const AlphaSearchSummary direct = search_tri_c(frame_net(boundary_of(elevated)), objective, lu(), options);
    const TriStudyCell& cell = row.cells[1];
    CHECK(cell.lower == options.lower);
    CHECK(cell.upper == options.upper);
    REQUIRE(cell.c.parameter.has_value() == direct.parameter.has_value());
    if (direct.parameter) CHECK(*cell.c.parameter == Approx(*direct.parameter).margin(1e-9));
    CHECK(cell.c.at_bound == direct.at_bound);
    // the reference values are the objective at c = -1/6 and c = 0, and no member found beats c*
    const double at_quadratic =
        evaluate_tri_objective(frame_net(boundary_of(elevated)), objective, -1.0 / 6, lu(), false).value;
    CHECK(cell.quadratic == Approx(at_quadratic));
    CHECK(cell.c.value <= std::min(cell.quadratic, cell.laplace) * (1 + 1e-9) + 1e-12);
  }
}

TEST_CASE("run_tri_study: a flat objective is reported flat, with no c, in results.json and the report",
          "[study][tri]") {
  const std::vector<TriStudyEntry> out = run_tri_study({planar_input(5)}, {6}, &lu());
  REQUIRE(out.size() == 1);
  const TriStudyRow& target = out[0].rows.back();
  REQUIRE(target.objective == "target");
  for (const TriStudyCell& cell : target.cells) {
    CHECK(cell.c.flat);
    CHECK_FALSE(cell.c.parameter);
  }
  const nlohmann::json j = tri_study_results_json(out);
  REQUIRE(j.size() == 1);
  CHECK(j[0]["kind"] == "triangle");
  CHECK(j[0]["degree"] == 5);
  CHECK(j[0]["solver"]["name"] == "eigen-lu");
  const nlohmann::json& cells = j[0]["objectives"]["target"];
  REQUIRE(cells.size() == 2);
  CHECK(cells[0]["c"].is_null());
  CHECK(cells[0]["flat"] == true);
  CHECK(cells[1]["degree"] == 6);
  // the thin plate of a curved planar boundary depends on c: an interior optimum or a bound, never flat
  CHECK(j[0]["objectives"]["thin_plate"][0]["flat"] == false);
  CHECK(j[0]["objectives"]["thin_plate"][0]["c"].is_number());

  const std::string md = tri_study_markdown(out, "6");
  CHECK(md.find("## 6. Triangular boundaries") != std::string::npos);
  CHECK(md.find("| target | 5 | flat | – |") != std::string::npos);
  CHECK(md.find("| target | 6 | flat | – |") != std::string::npos);
  CHECK(tri_study_markdown({}, "6").empty());
}

TEST_CASE("read_tri_study_input: the sides and the target of a triangular file", "[study][tri]") {
  const std::string path = (std::filesystem::temp_directory_path() / "coons_tri_study_input.json").string();
  nlohmann::json doc = tri_boundary_to_json(boundary_of(elevated_quadratic(4, 3), "quad"));
  doc["target"] = {{"sphere", {{"center", {0, 0, 0}}, {"radius", 2}}}};
  std::ofstream(path) << doc.dump();
  const TriStudyInput in = read_tri_study_input(path);
  std::remove(path.c_str());
  CHECK(in.boundary.n == 4);
  CHECK(in.boundary.name == "quad");
  REQUIRE(in.target);
  CHECK(in.target->kind == Target::Kind::kSphere);
  CHECK(in.target->radius == 2);
}

TEST_CASE("search_tri_c: an optimum the refinement leaves on a bound is reported at_bound", "[study][tri]") {
  // the monkey saddle elevated to n = 8, Dirichlet energy: c* = 1/3, the upper bound, with a slope
  // there that does not point outward; it used to be reported as an interior optimum
  const tri::TriBoundary b = read_tri_boundary_file(std::string(COONS_DATA_DIR) + "/triangles/monkey_saddle.json");
  const tri::TriNet elevated = elevate_degree(frame_net(b), 8 - b.n);
  std::string why;
  const TriObjective dirichlet = *parse_tri_objective("dirichlet", &why);
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(8);
  const AlphaSearchSummary s = search_tri_c(frame_net(boundary_of(elevated)), dirichlet, lu(), options);
  INFO(s.brief_report());
  REQUIRE(s.status == SearchStatus::kSuccess);
  REQUIRE(s.parameter);
  CHECK(*s.parameter == Approx(options.upper).margin(1e-9));
  CHECK(s.at_bound);
}
