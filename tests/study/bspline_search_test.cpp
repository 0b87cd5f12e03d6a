#include "coons/study/bspline_search.h"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>

#include "coons/study/bspline_net.h"
#include "coons/study/bspline_study.h"
#include "coons/surfaces/bspline_energy.h"
#include "solvers/registry.h"
#include "support/bspline_fixtures.h"
#include "support/bspline_singular.h"
#include "support/fixtures.h"
#include "support/near_singular_checks.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("bspline_alpha_objective: the derivative from one extra solve matches central differences",
          "[study][bspline]") {
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 7, 2, 6, 5));
  auto solver = solvers::make_solver("eigen-lu");
  for (const char* name : {"thin_plate", "e3", "twist+0.5*dirichlet", "discrete_thin_plate"}) {
    const Objective o = objective_named(name);
    const double alpha = -0.07, h = 1e-5;
    const auto at = bspline_alpha_objective(b, o, alpha, *solver);
    const auto plus = bspline_alpha_objective(b, o, alpha + h, *solver);
    const auto minus = bspline_alpha_objective(b, o, alpha - h, *solver);
    REQUIRE((at && plus && minus));
    INFO(name);
    CHECK(at->derivative == Approx((plus->value - minus->value) / (2 * h)).epsilon(1e-5).margin(1e-8));
  }
}

TEST_CASE("search_bspline_alpha: finds the minimum of a fine scan, twist has its minimum at the Coons net",
          "[study][bspline]") {
  // Random control points on random knots (repeated ones included): strongly non-uniform Greville
  // spacing, where the family is singular at some alpha > 0; searched in [-1/4, 0].
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  auto solver = solvers::make_solver("eigen-lu");
  for (const char* name : {"thin_plate", "e3"}) {
    const Objective o = objective_named(name);
    const AlphaSearchSummary s = search_bspline_alpha(b, o, "eigen-lu");
    REQUIRE(s.parameter);
    double best = HUGE_VAL;
    for (int k = 0; k <= 200; ++k)
      best = std::min(best, bspline_alpha_objective(b, o, -0.25 + 0.25 * k / 200, *solver)->value);
    INFO(name << ": alpha " << *s.parameter << ", status " << to_string(s.status));
    CHECK(s.value <= best * (1 + 1e-12));
    CHECK(s.value == Approx(bspline_alpha_objective(b, o, *s.parameter, *solver)->value).epsilon(1e-12));
    CHECK(s.solves == 2 * s.evaluations);  // inside [-1/4, 0]: the net and its derivative, no estimate
  }
  const AlphaSearchSummary twist = search_bspline_alpha(b, objective_named("twist"), "eigen-lu");
  REQUIRE(twist.parameter);
  CHECK(*twist.parameter == Approx(-0.25).margin(1e-8));
  CHECK(twist.at_bound);
  // higher degrees: the root of f' is found from inside, up to 1e-9 away, and is still the bound
  // (at_bound was false under a tolerance of 1e-10)
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    const BSplineBoundary high = compatible_boundary(make_random_bspline_boundary(5, 10, 6, 9, 40 + seed));
    const AlphaSearchSummary t = search_bspline_alpha(high, objective_named("twist"), "eigen-lu");
    INFO("seed " << seed << ": " << t.brief_report());
    REQUIRE(t.parameter);
    CHECK(std::abs(*t.parameter + 0.25) <= 1e-7 * 0.25);
    CHECK(t.at_bound);
  }
  const AlphaSearchSummary dirichlet = search_bspline_alpha(b, objective_named("dirichlet"), "eigen-lu");
  REQUIRE(dirichlet.parameter);
  CHECK(dirichlet.at_bound);
  CHECK(*dirichlet.parameter == 0.0);  // the default upper bound: [-1/4, 0] is where the system is definite
}

TEST_CASE("search_bspline_alpha: a boundary every alpha fills alike is flat, with no optimum claimed",
          "[study][bspline]") {
  // Bilinear data in the Greville abscissae: every member reproduces it (linear precision).
  const BSplineBoundary given = make_random_bspline_boundary(2, 6, 3, 5, 12);
  BSplineBoundary b = compatible_boundary(given);
  const GrevilleGrid grid = greville_grid(b);
  const auto f = [](double u, double v) { return Eigen::RowVector3d(u, v, 0.3 * u * v); };
  for (int i = 0; i <= grid.m(); ++i) {
    b.bottom.points.row(i) = f(grid.xi(i), 0);
    b.top.points.row(i) = f(grid.xi(i), 1);
  }
  for (int j = 0; j <= grid.n(); ++j) {
    b.left.points.row(j) = f(0, grid.eta(j));
    b.right.points.row(j) = f(1, grid.eta(j));
  }
  const AlphaSearchSummary s = search_bspline_alpha(b, objective_named("thin_plate"), "eigen-lu");
  CHECK(s.status == SearchStatus::kFlat);
  CHECK(s.flat);
  CHECK_FALSE(s.parameter);
}

TEST_CASE("run_bspline_study: one row per B-spline boundary with both energies and a verdict per objective",
          "[study][bspline]") {
  BSplineStudyInput in;
  in.name = "random";
  in.file = "random.json";
  in.sides.given = make_random_bspline_boundary(2, 6, 2, 5, 21);
  in.sides.compatible = compatible_boundary(in.sides.given, &in.sides.notes);
  std::vector<Objective> objectives = {objective_named("thin_plate"), objective_named("e3")};
  const std::vector<BSplineStudyRow> rows = run_bspline_study({in}, objectives, "");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].searches.size() == 2);
  CHECK(std::isfinite(rows[0].thin_plate_coons));
  CHECK(rows[0].thin_plate_laplace < rows[0].thin_plate_coons * 10);
  const std::string md = bspline_study_markdown(rows);
  CHECK(md.find("| random |") != std::string::npos);
  CHECK(bspline_study_json(rows)[0]["best_alpha"].contains("e3"));
}

TEST_CASE("bspline_definite_upper: the whole contract range on equal spacing, the definite end on repeated knots",
          "[study][bspline]") {
  // Bézier knots: equal Greville spacing, the α family of §3, definite on all of [−1/4, 1/4]
  BSplineSurface bezier;
  bezier.degree_u = 5;
  bezier.degree_v = 4;
  bezier.knots_u = bezier_knots(5);
  bezier.knots_v = bezier_knots(4);
  bezier.net = make_random_net(5, 4, 3);
  CHECK(bspline_definite_upper(boundary_of(bezier)) == 0.25);
  CHECK(bspline_search_options(boundary_of(bezier)).upper == 0.25);
  CHECK(bspline_search_options(boundary_of(bezier)).lower == -0.25);
  // random knots with repeated values: singular at some α in (0, 1/4]; the end lies just below the
  // first of them, where the system is still definite
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  const NonUniformMaskSystem s = assemble_nonuniform_mask_system(bspline_frame(b), greville_grid(b), 0);
  const Eigen::MatrixXd a0 = Eigen::MatrixXd(s.A), a1 = Eigen::MatrixXd(s.dA);
  const Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> pencil(a0, -a1);
  double first = HUGE_VAL;  // the smallest singular α above 0
  for (Eigen::Index k = 0; k < a0.rows(); ++k)
    if (std::abs(pencil.betas()(k)) > 1e-12 && std::abs(pencil.alphas()(k).imag()) <= 1e-9) {
      const double alpha = pencil.alphas()(k).real() / pencil.betas()(k);
      if (alpha > 0) first = std::min(first, alpha);
    }
  REQUIRE(first < 0.25);
  const double upper = bspline_definite_upper(b);
  INFO("first singular alpha " << first << ", definite upper " << upper);
  CHECK(upper < first);
  CHECK(upper > first - 0.01);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> at_upper(
      Eigen::MatrixXd(assemble_nonuniform_mask_system(bspline_frame(b), greville_grid(b), upper).A));
  CHECK(at_upper.eigenvalues().minCoeff() > 0);  // (symmetric: rows scaled, docs/math.md §10)
  // the search's default bounds end there, and its optimum is a minimum of a fine scan up to it
  const AlphaSearchSummary thin =
      search_bspline_alpha(b, objective_named("thin_plate"), "eigen-lu", bspline_search_options(b));
  REQUIRE(thin.parameter);
  CHECK(*thin.parameter <= upper);
  auto solver = solvers::make_solver("eigen-lu");
  const AlphaSearchOptions bounds = bspline_search_options(b);
  double lowest = HUGE_VAL;  // a scan 1/400 of the bounds apart, up to the definite end
  for (int i = 0; i <= 400; ++i) {
    const double alpha = bounds.lower + (bounds.upper - bounds.lower) * i / 400;
    if (const auto v = bspline_alpha_objective(b, objective_named("thin_plate"), alpha, *solver))
      lowest = std::min(lowest, v->value);
  }
  REQUIRE(lowest < HUGE_VAL);
  CHECK(thin.value <= lowest * (1 + 1e-12));
}

TEST_CASE("bspline_pole_note: an optimum against a definite end cut by a singular alpha is said to be its",
          "[study][bspline]") {
  AlphaSearchOptions options = default_bspline_search_options();
  options.upper = 0.1164;
  AlphaSearchSummary s;
  s.parameter = 0.1149;  // bspline_wave's Dirichlet optimum, 0.0015 below its singular end
  CHECK_THAT(bspline_pole_note(s, options, 0.1164), Catch::Contains("so this minimum is made by it"));
  CHECK_THAT(bspline_pole_note(s, options, 0.1164), Catch::StartsWith("the optimum lies 0.0015 below 0.1164"));
  s.parameter = 0.1164;  // on the end itself, the objective still falling there (spans of 2e-9: "rises" was said)
  s.at_bound = true;
  CHECK_THAT(bspline_pole_note(s, options, 0.1164), Catch::Contains("where the objective still falls"));
  CHECK_THAT(bspline_pole_note(s, options, 0.1164), Catch::StartsWith("the optimum is 0.1164, the end of the range"));
  s.at_bound = false;
  s.parameter = -0.0866;  // its thin-plate optimum: far from the end
  CHECK(bspline_pole_note(s, options, 0.1164).empty());
  s.parameter = 0.249;  // an end at 1/4 is the contract's bound, not a singular alpha
  options.upper = 0.25;
  CHECK(bspline_pole_note(s, options, 0.25).empty());
  s.parameter.reset();
  CHECK(bspline_pole_note(s, options, 0.1164).empty());
}

TEST_CASE("search_bspline_alpha: a near-singular alpha is a failed evaluation and never the optimum",
          "[study][bspline]") {
  // random knots with repeated values: the non-uniform system is singular at some α in (0, 1/4];
  // the scan's lower bound lies 1e-9 above it
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  const double star = bspline_singular_alpha(b);
  REQUIRE(star < 0.25);
  AlphaSearchOptions options = default_bspline_search_options();
  options.lower = star + 1e-9;
  options.upper = star + 0.02;
  const AlphaSearchSummary s = search_bspline_alpha(b, objective_named("thin_plate"), "eigen-lu", options);
  INFO("singular alpha " << star << ": " << s.brief_report());
  test::check_refused_near_singular(s, options, star);
  // every evaluation above 0 estimates its ratio first (three solves at least), and says so
  CHECK(s.solves >= 3 * s.evaluations);
  CHECK(s.solves > 2 * s.evaluations);
  // the objective names the ratio
  auto solver = solvers::make_solver("eigen-lu");
  solvers::SolveStatus status = solvers::SolveStatus::kSuccess;
  CHECK_FALSE(bspline_alpha_objective(b, objective_named("thin_plate"), star + 1e-9, *solver, &status));
  CHECK(status == solvers::SolveStatus::kSingular);
  CHECK(bspline_alpha_objective(b, objective_named("thin_plate"), star + 1e-3, *solver));
}

TEST_CASE("search_bspline_alpha: failures away from the optimum are named, and the optimum stands",
          "[study][bspline]") {
  // the same boundary, searched from −1/4 up to 1e-9 above its singular α: only the top of the
  // scan fails, far from the optimum
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  const double star = bspline_singular_alpha(b);
  AlphaSearchOptions options = default_bspline_search_options();
  options.lower = -0.25;
  options.upper = star + 1e-9;
  const AlphaSearchSummary s = search_bspline_alpha(b, objective_named("thin_plate"), "eigen-lu", options);
  INFO("singular alpha " << star << ": " << s.brief_report());
  CHECK(s.status == SearchStatus::kSuccess);
  REQUIRE(s.parameter);
  CHECK(*s.parameter < star - 0.05);
  CHECK(s.failed_evaluations == 1);
  REQUIRE(s.failed_intervals.size() == 1);
  CHECK(s.failed_intervals.front().first == options.upper);
  CHECK(s.first_failure == solvers::SolveStatus::kSingular);
  CHECK(s.message.find("1 evaluation(s) failed at") != std::string::npos);
  CHECK(s.message.find("away from the optimum") != std::string::npos);
}

TEST_CASE("search_bspline_alpha: the scan ends on the upper bound exactly", "[study][bspline]") {
  // −0.25 + (−0.085 + 0.25)·10/10 = −0.08500000000000002 in doubles: the last scan point was an
  // ulp off the bound (the Bézier search takes the bound itself)
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 9));
  AlphaSearchOptions options = default_bspline_search_options();
  options.upper = -0.085;
  options.scan_points = 11;
  const AlphaSearchSummary s = search_bspline_alpha(b, objective_named("thin_plate"), "eigen-lu", options);
  REQUIRE(s.scan.size() == 11);
  CHECK(s.scan.front().first == options.lower);
  CHECK(s.scan.back().first == options.upper);
}

TEST_CASE("search_bspline_alpha, make_bspline_net: a boundary moved by 1e12 keeps its optimum and energies",
          "[study][bspline]") {
  // Points on a grid of 2^-10 move to 1e12 and back exactly, so both boundaries are one shape. Solved
  // and measured where they lie, the far one lost the shape's digits: e3 1.5 % off, α* of e3 at
  // -0.00186 against -0.000397.
  BSplineBoundary near = compatible_boundary(make_random_bspline_boundary(3, 8, 2, 6, 12));
  for (BSplineCurve* side : {&near.bottom, &near.top, &near.left, &near.right})
    side->points = side->points.unaryExpr([](double x) { return std::ldexp(std::round(std::ldexp(x, 10)), -10); });
  const BSplineBoundary far = bspline_translated(near, Eigen::RowVector3d::Constant(1e12));
  REQUIRE((bspline_translated(far, Eigen::RowVector3d::Constant(-1e12)).bottom.points - near.bottom.points).norm() ==
          0);
  auto solver = solvers::make_solver("eigen-lu");
  const BSplineNetOutcome a = make_bspline_net(near, NetMethod::kAlpha, -0.1, solver.get());
  const BSplineNetOutcome b = make_bspline_net(far, NetMethod::kAlpha, -0.1, solver.get());
  REQUIRE(a.summary->ok());
  REQUIRE(b.summary->ok());
  const NetMetrics ma = bspline_metrics(a.local, -0.1), mb = bspline_metrics(b.local, -0.1);
  CHECK(mb.e3_energy == Approx(ma.e3_energy).epsilon(1e-10));
  CHECK(mb.twist_energy == Approx(ma.twist_energy).epsilon(1e-10));
  CHECK(mb.mask_residual <= 1e-12);
  for (const char* name : {"e3", "twist"}) {
    const AlphaSearchSummary sa = search_bspline_alpha(near, objective_named(name), "eigen-lu");
    const AlphaSearchSummary sb = search_bspline_alpha(far, objective_named(name), "eigen-lu");
    INFO(name << ": " << sa.brief_report() << " / " << sb.brief_report());
    REQUIRE(sa.parameter);
    REQUIRE(sb.parameter);
    CHECK(*sb.parameter == Approx(*sa.parameter).margin(1e-9));
    CHECK(sb.value == Approx(sa.value).epsilon(1e-10));
  }
}
