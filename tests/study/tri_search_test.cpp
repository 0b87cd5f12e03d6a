#include "coons/study/tri_search.h"

#include <catch2/catch.hpp>

#include "coons/tri/tri_energy.h"
#include "tri/tri_fixtures.h"

using namespace coons;
using namespace coons::tri;
using namespace coons::tri_test;

namespace {

TriObjective objective(const std::string& text) {
  std::string why;
  const auto o = parse_tri_objective(text, &why);
  INFO(why);
  REQUIRE(o);
  return *o;
}

}  // namespace

TEST_CASE("parse_tri_objective: names and weighted sums, unknown names are refused", "[study][tri]") {
  const TriObjective o = objective("thin_plate+0.5*twist+2*discrete_dirichlet");
  REQUIRE(o.terms.size() == 3);
  REQUIRE(o.terms[1] == std::make_pair(TriTerm::kTwist, 0.5));
  REQUIRE(o.terms[2] == std::make_pair(TriTerm::kDiscreteDirichlet, 2.0));
  REQUIRE_FALSE(o.uses_target());
  REQUIRE(objective("target").uses_target());
  std::string why;
  for (const char* bad : {"e3", "thin_plate+", "-1*twist", "x*twist", ""}) {
    INFO(bad);
    REQUIRE_FALSE(parse_tri_objective(bad, &why));
    REQUIRE_FALSE(why.empty());
  }
}

TEST_CASE("evaluate_tri_objective: the derivative from one extra solve equals a central difference", "[study][tri]") {
  Target sphere;
  sphere.kind = Target::Kind::kSphere;
  sphere.radius = 1.5;
  sphere.samples = 9;
  for (const int n : {3, 5, 8}) {
    const TriNet frame = frame_net(boundary_of(random_tri_net(n, 40 + n)));
    for (const char* name : {"thin_plate", "dirichlet", "twist", "discrete_thin_plate", "discrete_dirichlet",
                             "discrete_twist", "target", "thin_plate+3*target"}) {
      TriObjective o = objective(name);
      o.target = sphere;
      for (const double c : {-0.15, 0.0, 0.2}) {
        const TriEvaluation e = evaluate_tri_objective(frame, o, c, lu(), true);
        REQUIRE(e.ok());
        const double h = 1e-5;
        const double plus = evaluate_tri_objective(frame, o, c + h, lu(), false).value;
        const double minus = evaluate_tri_objective(frame, o, c - h, lu(), false).value;
        const double difference = (plus - minus) / (2 * h);
        INFO(name << ", n = " << n << ", c = " << c << ": " << e.derivative << " vs " << difference);
        REQUIRE(e.derivative == Approx(difference).epsilon(1e-6).margin(1e-8 * (1 + std::abs(e.value))));
      }
    }
  }
}

TEST_CASE("evaluate_tri_objective: the derivative does not depend on where the boundary lies", "[study][tri]") {
  TriNet net = random_tri_net(7, 90);
  const TriNet frame = frame_net(boundary_of(net));
  net.points.rowwise() += Eigen::RowVector3d(3e5, -2e5, 1e5);
  const TriNet moved = frame_net(boundary_of(net));
  for (const char* name : {"thin_plate", "dirichlet", "twist", "discrete_twist"}) {
    const TriEvaluation here = evaluate_tri_objective(frame, objective(name), -0.1, lu(), true);
    const TriEvaluation there = evaluate_tri_objective(moved, objective(name), -0.1, lu(), true);
    INFO(name << ": " << here.derivative << " vs " << there.derivative);
    REQUIRE(there.derivative == Approx(here.derivative).epsilon(1e-6).margin(1e-9 * here.value));
  }
}

TEST_CASE("search_tri_c: the optimum is the minimum of a fine scan, inside the bounds", "[study][tri]") {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    const int n = 5 + int(seed);
    const TriNet frame = frame_net(boundary_of(random_tri_net(n, 500 + seed)));
    const TriObjective o = objective("thin_plate");
    AlphaSearchOptions options;
    std::tie(options.lower, options.upper) = default_tri_bounds(n);
    const AlphaSearchSummary s = search_tri_c(frame, o, lu(), options);
    REQUIRE(s.status == SearchStatus::kSuccess);
    REQUIRE(s.parameter);
    double best = HUGE_VAL, best_c = 0;
    for (int k = 0; k <= 400; ++k) {
      const double c = options.lower + (options.upper - options.lower) * k / 400;
      const double v = evaluate_tri_objective(frame, o, c, lu(), false).value;
      if (v < best) best = v, best_c = c;
    }
    INFO("seed " << seed << ": search " << *s.parameter << " (" << s.value << "), scan " << best_c << " (" << best
                 << ")");
    REQUIRE(s.value <= best * (1 + 1e-12));
    REQUIRE(std::abs(*s.parameter - best_c) <= (options.upper - options.lower) / 400);
    if (!s.at_bound)
      REQUIRE(std::abs(evaluate_tri_objective(frame, o, *s.parameter, lu(), true).derivative) < 1e-6 * s.value);
  }
}

TEST_CASE("search_tri_c: an affine boundary is flat, no optimum is claimed", "[study][tri]") {
  const TriNet frame = frame_net(boundary_of(elevated_linear(7, 3)));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(7);
  for (const char* name : {"thin_plate", "dirichlet", "twist"}) {
    const AlphaSearchSummary s = search_tri_c(frame, objective(name), lu(), options);
    REQUIRE(s.status == SearchStatus::kFlat);
    REQUIRE(s.flat);
    REQUIRE_FALSE(s.parameter);
  }
}

TEST_CASE("default_tri_bounds: between the singular member c*_n and 1/3, around -1/6", "[study][tri]") {
  for (int n = 3; n <= 40; ++n) {
    const auto [lower, upper] = default_tri_bounds(n);
    REQUIRE(lower < -1.0 / 6);
    REQUIRE(upper == Approx(1.0 / 3));
    if (n >= 4) REQUIRE(lower > -1.0 / 6 - 1.0 / (2.0 * (n - 3)));
  }
}

TEST_CASE("search_tri_c: a Cholesky-type backend fails the search instead of giving a wrong optimum", "[study][tri]") {
  const TriNet frame = frame_net(boundary_of(random_tri_net(6, 77)));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(6);
  const AlphaSearchSummary s =
      search_tri_c(frame, objective("thin_plate"), *solvers::find_solver("eigen-ldlt"), options);
  REQUIRE((s.status == SearchStatus::kFailedRegion || s.status == SearchStatus::kSolverFailed));
  REQUIRE_FALSE(s.parameter);
  REQUIRE(s.failed_evaluations > 0);
}

TEST_CASE("search_tri_c: consecutive failed evaluations are reported as one failed interval", "[study][tri]") {
  // a Cholesky-type backend takes only c = 0 (the symmetric member): the scan points below and above
  // it fail, two runs of two points each
  const TriNet frame = frame_net(boundary_of(random_tri_net(6, 77)));
  AlphaSearchOptions options;
  options.lower = -0.5;
  options.upper = 0.5;
  options.scan_points = 5;
  const AlphaSearchSummary s =
      search_tri_c(frame, objective("thin_plate"), *solvers::find_solver("eigen-ldlt"), options);
  CHECK(s.status == SearchStatus::kFailedRegion);
  CHECK(s.failed_evaluations == 4);
  const std::vector<std::pair<double, double>> runs = {{-0.5, -0.25}, {0.25, 0.5}};
  CHECK(s.failed_intervals == runs);
}
