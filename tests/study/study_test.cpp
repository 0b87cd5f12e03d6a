// The α study as a library (coons/study/study.h): entries, kinds and reference tables without the CLI.
#include "coons/study/study.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/alpha/family_search.h"
#include "coons/io/net_json.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/study/provenance.h"
#include "coons/study/report_markdown.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;

namespace {

StudyInput input(const std::string& name, Boundary b, std::optional<Target> target = std::nullopt) {
  b.name = name;
  StudyInput in;
  in.file = name + ".json";
  in.boundary = std::move(b);
  in.target = std::move(target);
  return in;
}

// The report's figures of a study result, none drawn (every one with its reason).
StudyFigures figures_not_drawn(const StudyResult& r) {
  StudyFigures figures;
  for (size_t k = 0; k < r.shapes.size(); ++k) {
    figures.energies.push_back({"figures/x.png", "not drawn in this test"});
    figures.nets.push_back({"figures/y.png", "not drawn in this test"});
  }
  figures.alpha_vs_degree = {"figures/a.png", "not drawn"};
  figures.mu_vs_degree = {"figures/m.png", "not drawn"};
  return figures;
}

}  // namespace

TEST_CASE("run_study: two boundaries made in code give their shape, degree-law and reference entries", "[study]") {
  Target plane;
  plane.kind = Target::Kind::kPlane;
  plane.point = {0, 0, 0};
  plane.direction = {0, 0, 1};
  const std::vector<StudyInput> inputs = {input("smooth", make_smooth_boundary(3, 3, 7), plane),
                                          input("wide", make_smooth_boundary(4, 3, 9))};
  StudyOptions options;
  options.degrees = {4, 6};
  options.solver = &backend("eigen-ldlt");
  std::string why;
  REQUIRE(options.is_valid(&why));
  const StudyResult r = run_study(inputs, options);

  REQUIRE(r.shapes.size() == 2);
  CHECK(r.shapes[0].boundary.name == "smooth");
  REQUIRE(r.shapes[0].optima.size() == 2);  // thin_plate and e3
  CHECK(r.shapes[0].optima[0].objective == "thin_plate");
  CHECK(r.shapes[0].curves.size() == 41);
  // the Coons value is the objective at α = −1/4: thin plate of the discrete Coons net
  CHECK(r.shapes[0].optima[0].coons ==
        Approx(thin_plate_energy(discrete_coons_net(inputs[0].boundary))).epsilon(1e-10));
  // the degree law: "smooth" (3×3) is elevated to 4 and 6; "wide" (4×3) to 4 and 6 as well
  REQUIRE(r.laws.size() == 4);
  CHECK(r.laws[0].boundary == "smooth");
  CHECK(r.laws[0].cells.size() == 2);
  CHECK(r.laws[2].boundary == "wide");
  CHECK(r.laws[2].cells.front().degree == 4);
  // no curves, so no fit deviations; one target, so one reference table with four rows
  CHECK(r.fit_deviations.empty());
  REQUIRE(r.references.size() == 1);
  CHECK(r.references[0].boundary == "smooth");
  REQUIRE(r.references[0].rows.size() == 4);
  CHECK(r.references[0].rows[0].alpha == -0.25);
  CHECK(r.references[0].rows[0].thin_plate == Approx(r.shapes[0].optima[0].coons).epsilon(1e-10));
  // the plane z = 0: rms distance of the Coons net's surface to it
  const ControlNet coons = discrete_coons_net(inputs[0].boundary);
  CHECK(r.references[0].coons_rms == Approx(rms_distance(coons, plane)).epsilon(1e-12));
  CHECK(r.references[0].best.value <= r.references[0].coons_rms + 1e-15);

  const json results = study_results_json(r);
  std::map<std::string, int> kinds;
  for (const auto& e : results) ++kinds[e["kind"].get<std::string>()];
  CHECK(kinds["shape"] == 2);
  CHECK(kinds["degree_law"] == 4);
  CHECK(kinds["reference_table"] == 1);
  CHECK(kinds.count("fit_deviation") == 0);
  for (const auto& e : results)
    if (e["kind"] == "reference_table") {
      CHECK(e["rows"].size() == 4);
      CHECK(e["rows"][1]["alpha"] == -0.2);
      CHECK(e["coons_rms_target"].get<double>() == Approx(r.references[0].coons_rms));
    }

  // the report prints the reference table of any boundary with a target, by its own name
  const std::string md = study_report_markdown(r, current_provenance("test"), figures_not_drawn(r));
  CHECK_THAT(md, Catch::Contains("### smooth (3×3)"));
  CHECK_THAT(md, Catch::Contains("rms distance to the target"));
  CHECK_THAT(md, !Catch::Contains("### wide (4×3)"));
  // no input has two data rings: no C1 column, no weight fields (the output of the α study alone)
  CHECK_THAT(md, !Catch::Contains("w* (C1 family)"));
  for (const auto& e : results)
    if (e["kind"] == "shape") {
      CHECK_FALSE(e.contains("weight_solver"));
      CHECK_FALSE(e["thin_plate"].contains("weight"));
    }
}

TEST_CASE(
    "run_study: an input with two data rings gets w* of the C1 family beside alpha*, others a dash with the reason",
    "[study]") {
  // the two rings: a random net's frame and second ring, the inside free
  ControlNet net = make_random_net(6, 6, 31);
  StudyInput ribbons = input("ribbons", boundary_of(net));
  ribbons.two_rings = rings_problem(net, 2);
  StudyInput plain = input("plain", make_smooth_boundary(4, 4, 9));
  plain.one_ring = "ribbons: missing";
  StudyOptions options;
  options.degrees = {6};
  options.solver = &backend("mg");  // no matrix: the weight searches take a direct backend instead
  const StudyResult r = run_study({ribbons, plain}, options);
  REQUIRE(r.shapes.size() == 2);
  REQUIRE(r.shapes[0].optima.size() == 2);  // thin_plate and e3, the default objectives
  REQUIRE(r.shapes[1].optima.size() == 2);
  for (const ShapeOptimum& o : r.shapes[0].optima) {
    REQUIRE(o.weight);
    INFO(o.objective << ": " << o.weight->brief_report());
    CHECK(o.weight->status == SearchStatus::kSuccess);
    REQUIRE(o.weight->parameter);
    // the reported value is the objective of the net the C1 stencil gives at w*
    const Objective objective = *parse_objective(o.objective, nullptr);
    const AlphaSearchSummary again = search_weight(*ribbons.two_rings, objective, backend("eigen-ldlt"));
    REQUIRE(again.parameter);
    CHECK(*o.weight->parameter == Approx(*again.parameter).margin(1e-8));
    CHECK(o.weight->value == Approx(again.value).epsilon(1e-12));
  }
  CHECK(r.shapes[0].weight_solver != "fast");
  for (const ShapeOptimum& o : r.shapes[1].optima) CHECK_FALSE(o.weight);

  const json results = study_results_json(r);
  REQUIRE(results[0]["kind"] == "shape");
  const json& tp = results[0]["thin_plate"];
  CHECK(tp["weight"].get<double>() == *r.shapes[0].optima[0].weight->parameter);
  CHECK(tp["weight_value"].get<double>() == r.shapes[0].optima[0].weight->value);
  for (const char* key : {"weight_flat", "weight_at_bound", "weight_status"}) CHECK(tp.contains(key));
  CHECK(results[0].contains("weight_solver"));
  CHECK_FALSE(results[1]["thin_plate"].contains("weight"));

  const std::string md = study_report_markdown(r, current_provenance("test"), figures_not_drawn(r));
  CHECK_THAT(md, Catch::Contains("| w* (C1 family) | value at w* |"));
  CHECK_THAT(md, Catch::Contains("| – (ribbons: missing) | – |"));
}

TEST_CASE("StudyOptions: degrees out of range, repeated or unordered are refused", "[study]") {
  StudyOptions o;
  std::string why;
  CHECK(o.is_valid(&why));
  o.degrees = {1, 4};
  CHECK(!o.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("[2, 200]"));
  o.degrees = {6, 4};
  CHECK(!o.is_valid(&why));
  o.degrees = {4, 4};
  CHECK(!o.is_valid(&why));
}

TEST_CASE("shape_file_stems: repeated names get their degree, unsafe names are made safe", "[study]") {
  StudyResult r;
  for (auto [name, m] : {std::pair<std::string, int>{"dome", 3}, {"dome", 6}, {"../escaped", 3}, {"dome", 3}}) {
    ShapeEntry s;
    s.boundary = make_smooth_boundary(m, m, 1);
    s.boundary.name = name;
    r.shapes.push_back(s);
  }
  const auto stems = shape_file_stems(r);
  CHECK(stems[0] == "dome");
  CHECK(stems[1] == "dome-6x6");
  CHECK(stems[2].find('/') == std::string::npos);
  CHECK(stems[3] != stems[0]);
  CHECK(stems[3] != stems[1]);
}

TEST_CASE("utc_iso8601: a fixed time point in ISO 8601, UTC", "[study]") {
  const auto t = std::chrono::system_clock::from_time_t(1795000000);  // 2026-11-18T11:06:40Z
  CHECK(utc_iso8601(t) == "2026-11-18T11:06:40Z");
  const Provenance p = current_provenance("coons study x");
  CHECK(p.command_line == "coons study x");
  CHECK(p.date.size() == 20);
  CHECK(!p.version.empty());
}

TEST_CASE("provenance_line: the command, date and versions, the git revision only when known", "[study]") {
  Provenance p{"coons study data/x.json", "2026-11-18T11:06:40Z", "0.1.0", "abc1234", "3.4.0", "2.1.0"};
  CHECK(provenance_line(p) ==
        "Generated by `coons study data/x.json` on 2026-11-18T11:06:40Z (coons 0.1.0, git abc1234, Eigen 3.4.0, "
        "Ceres 2.1.0). Every number below is computed by this run.");
  p.git_revision.clear();
  CHECK(provenance_line(p).find("(coons 0.1.0, Eigen 3.4.0,") != std::string::npos);
}

TEST_CASE("read_study_input: a net with rings 2 gives the two-ring problem, one ring gives the reason", "[study]") {
  TempDir dir;
  const ControlNet net = make_random_net(6, 5, 8);
  json doc = {{"name", "r"}, {"net", net_to_json(net)}, {"rings", 2}};
  const StudyInput two = read_study_input(dir.write("two.json", doc.dump()));
  REQUIRE(two.two_rings);
  CHECK(two.two_rings->rings == 2);
  CHECK(max_difference(two.two_rings->net, net) == 0);
  CHECK(two.one_ring.empty());
  doc["rings"] = 1;
  const StudyInput one = read_study_input(dir.write("one.json", doc.dump()));
  CHECK_FALSE(one.two_rings);
  CHECK(one.one_ring == "one data ring, rings 1");
  const StudyInput sides = read_study_input(dir.write("sides.json", boundary_to_json(boundary_of(net)).dump()));
  CHECK_FALSE(sides.two_rings);
  CHECK(sides.one_ring == "one data ring, no ribbons");
}

namespace {

// A study result made in code: one 3×3 shape whose thin-plate searches found their optima.
StudyResult one_shape_result() {
  StudyResult r;
  r.degrees = {3};
  r.objectives = {"thin_plate"};
  ShapeEntry shape;
  shape.file = "bump.json";
  shape.boundary = make_smooth_boundary(3, 3, 5);
  shape.boundary.name = "bump";
  shape.solver = "eigen-ldlt";
  ShapeOptimum o;
  o.objective = "thin_plate";
  o.alpha.parameter = -0.1;
  o.alpha.value = 2.5;
  o.alpha.solves = 7;
  o.mu.parameter = 20;
  o.mu.value = 2.5;
  o.mu.solves = 5;
  o.coons = 3;
  o.laplace = 4;
  shape.optima.push_back(o);
  r.shapes.push_back(shape);
  return r;
}

}  // namespace

TEST_CASE("study_results_json: a shape with a failed region or a failed solve says solver status failure", "[study]") {
  StudyResult r = one_shape_result();
  const json good = study_results_json(r)[0]["solver"];
  CHECK(good["status"] == "success");
  CHECK(good["iterations"] == 12);  // the linear solves of the α* and μ* searches
  CHECK_FALSE(good.contains("message"));
  // μ* rests on failed solves: no optimum claimed, and the block says so
  r.shapes[0].optima[0].mu.status = SearchStatus::kFailedRegion;
  r.shapes[0].optima[0].mu.parameter.reset();
  const json region = study_results_json(r)[0]["solver"];
  CHECK(region["status"] == "failure");
  CHECK(region["message"] == "thin_plate: μ* failed_region");
  // the solve at α = 0 failed (its value is null in the entry)
  r = one_shape_result();
  r.shapes[0].optima[0].laplace = std::numeric_limits<double>::quiet_NaN();
  const json entry = study_results_json(r)[0];
  CHECK(entry["thin_plate"]["laplace"].is_null());
  CHECK(entry["solver"]["status"] == "failure");
}

TEST_CASE("study_report_markdown: the Coons-to-best ratio has three significant digits, not a rounded integer",
          "[study]") {
  StudyResult r = one_shape_result();
  ReferenceTable t{"bump", 3, 3, {}, {}, 1.34};
  t.best.parameter = -0.2;
  t.best.value = 1.0;
  r.references.push_back(t);
  const std::string md = study_report_markdown(r, current_provenance("test"), figures_not_drawn(r));
  CHECK_THAT(md, Catch::Contains("against 1.34 for the Coons net: 1.34× closer"));
}

TEST_CASE("study_report_markdown: a value beside a failed region is labelled as found outside it", "[study]") {
  StudyResult r = one_shape_result();
  AlphaSearchSummary& alpha = r.shapes[0].optima[0].alpha;
  alpha.status = SearchStatus::kFailedRegion;
  alpha.parameter.reset();
  alpha.value = 2.75;
  const std::string md = study_report_markdown(r, current_provenance("test"), figures_not_drawn(r));
  CHECK_THAT(md, Catch::Contains("| bump | 3×3 | thin_plate | failed region | 2.75 (outside the failed region) |"));
  // no evaluation succeeded: no value at all
  alpha.status = SearchStatus::kSolverFailed;
  alpha.value = 0;
  const std::string none = study_report_markdown(r, current_provenance("test"), figures_not_drawn(r));
  CHECK_THAT(none, Catch::Contains("| bump | 3×3 | thin_plate | failed | – |"));
}
