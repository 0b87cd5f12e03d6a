#include "coons/study/bspline_net.h"

#include <catch2/catch.hpp>
#include <random>

#include "coons/io/bspline_boundary_io.h"
#include "coons/surfaces/bspline_energy.h"
#include "solvers/registry.h"
#include "support/bspline_fixtures.h"
#include "support/bspline_singular.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The largest distance on a k × k grid of [0, 1]² between the surface and the continuous
// bilinearly blended Coons patch of the given (not yet compatible) sides.
double distance_to_patch(const BSplineSurface& s, const BSplineBoundary& given, int k) {
  double worst = 0;
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const double u = double(a) / (k - 1), v = double(b) / (k - 1);
      worst = std::max(worst, (evaluate(s, u, v) - coons_patch_point(given, u, v)).norm());
    }
  return worst;
}

}  // namespace

TEST_CASE("make_bspline_net: random knot vectors give the continuous Coons patch (coons, alpha = -1/4)",
          "[study][bspline]") {
  // Evidence (issue 12): sizes, degrees and knots drawn at random; opposite sides differ in degree,
  // knots, point count and domain, so every case goes through compatible_boundary first.
  std::mt19937 random(20261122);
  auto solver = solvers::make_solver("eigen-ldlt");
  int cases = 0;
  double worst = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int p = 1 + int(random() % 5), q = 1 + int(random() % 5);
    const int count_u = p + 1 + int(random() % 9), count_v = q + 1 + int(random() % 7);
    const BSplineBoundary given = make_random_bspline_boundary(p, count_u, q, count_v, std::uint32_t(random()));
    const BSplineBoundary compatible = compatible_boundary(given);
    const BSplineNetOutcome coons = make_bspline_net(compatible, NetMethod::kCoons, -0.25, nullptr);
    const BSplineNetOutcome alpha = make_bspline_net(compatible, NetMethod::kAlpha, -0.25, solver.get());
    REQUIRE(alpha.summary);
    REQUIRE(alpha.summary->ok());
    INFO("trial " << trial << ": p = " << p << ", q = " << q << ", points " << count_u << " x " << count_v);
    const double d_coons = distance_to_patch(coons.surface, given, 23);
    const double d_alpha = distance_to_patch(alpha.surface, given, 23);
    CHECK(d_coons < 1e-11);
    CHECK(d_alpha < 1e-9);
    worst = std::max({worst, d_coons, d_alpha});
    cases += coons.surface.net.m != coons.surface.net.n ? 1 : 0;
  }
  INFO("worst distance " << worst);
  CHECK(cases > 40);  // most draws have m != n
}

TEST_CASE("make_bspline_net: on Bézier knot vectors the alpha family is the uniform family of docs/math.md §3",
          "[study][bspline]") {
  const ControlNet source = make_random_net(5, 3, 3);
  const Boundary b = boundary_of(source, "bezier");
  BSplineKnots knots;
  knots.degree_u = 5;
  knots.degree_v = 3;
  knots.knots_u = bezier_knots(5);
  knots.knots_v = bezier_knots(3);
  const BSplineInput in = bspline_input(b, knots, "fixture");
  CHECK(in.notes.empty());
  auto solver = solvers::make_solver("eigen-lu");
  for (const double alpha : {-0.25, -0.1, 0.0, 0.2}) {
    const BSplineNetOutcome bs = make_bspline_net(in.compatible, NetMethod::kAlpha, alpha, solver.get());
    const NetOutcome bezier = make_net(b, NetMethod::kAlpha, alpha_mask(alpha), &backend("eigen-lu"));
    REQUIRE(bs.summary->ok());
    CHECK((bs.surface.net.points - bezier.net.points).cwiseAbs().maxCoeff() < 1e-12);
    const NetMetrics exact = net_metrics(bezier.net, alpha_mask(alpha));
    const NetMetrics ours = bspline_metrics(bs.surface, alpha);
    CHECK(ours.thin_plate_energy == Approx(exact.thin_plate_energy).epsilon(1e-10));
    CHECK(ours.e3_energy == Approx(exact.e3_energy).epsilon(1e-10));
    CHECK(ours.mask_residual < 1e-12);
  }
}

TEST_CASE("bspline_net_report: names the knots, the degrees and what compatibility changed", "[study][bspline]") {
  const BSplineBoundary given = make_random_bspline_boundary(2, 6, 3, 5, 17);
  BSplineInput in;
  in.given = given;
  in.compatible = compatible_boundary(given, &in.notes);
  REQUIRE_FALSE(in.notes.empty());
  const BSplineNetOutcome coons = make_bspline_net(in.compatible, NetMethod::kCoons, -0.25, nullptr);
  const nlohmann::json r = bspline_net_report("random", in, NetMethod::kCoons, -0.25, coons, false);
  CHECK(r["method"] == "coons");
  CHECK(r["degree"][0] == coons.surface.net.m);
  CHECK(r["bspline"]["degree_spline"][0] == in.compatible.bottom.degree);
  CHECK(r["bspline"]["knots_u"].size() == std::size_t(coons.surface.knots_u.size()));
  CHECK(r["bspline"]["compatibility"].size() == in.notes.size());
  CHECK(r["bspline"]["compatibility"][0]["side"] == in.notes[0].side);
  CHECK(r["net"].size() == std::size_t(coons.surface.net.m + 1));
  CHECK(r["metrics"]["thin_plate_energy"].get<double>() ==
        Approx(bspline_combined_energy(coons.surface, bspline_thin_plate_terms())));
  CHECK(r["metrics"]["mask_residual"].get<double>() < 1e-12);
}

TEST_CASE("make_bspline_net: a singular alpha is refused as singular and not solved into a net", "[study][bspline]") {
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  const double star = bspline_singular_alpha(b);
  REQUIRE(star < 0.25);
  auto solver = solvers::make_solver("eigen-lu");
  const BSplineNetOutcome at = make_bspline_net(b, NetMethod::kAlpha, star + 1e-12, solver.get());
  REQUIRE(at.summary);
  INFO("singular alpha " << star << ": " << at.summary->brief_report());
  CHECK(at.summary->status == solvers::SolveStatus::kSingular);
  CHECK_THAT(at.summary->message, Catch::Contains("min|eigenvalue|/max|eigenvalue|"));
  // not solved: the residual of X = 0 (1), never the 0 of a perfect solve
  CHECK(at.summary->relative_residual == 1);
  // a little farther the system is regular (a ratio far above 1e-10) and is solved
  const BSplineNetOutcome near = make_bspline_net(b, NetMethod::kAlpha, star + 1e-4, solver.get());
  REQUIRE(near.summary);
  CHECK(near.summary->ok());
}
