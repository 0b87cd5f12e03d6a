#include "coons/alpha/family_search.h"

#include <Eigen/Eigenvalues>
#include <boost/math/tools/minima.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/stencil_family_objective.h"
#include "coons/mask/solve_stencil_net.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_system.h"
#include "coons/net/coons_net.h"
#include "support/fixtures.h"
#include "support/near_singular_checks.h"

using namespace coons;
using namespace coons::test;

namespace {

// A smooth random surface sampled on the (m+1)×(n+1) grid: a random cubic in (u, v) plus a
// random wave, so that no member of the C1 family reproduces it. Two data rings.
StencilProblem ribbon_problem(int m, int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> c(-1, 1);
  Eigen::Matrix<double, 16, 3> coefficients;
  for (int r = 0; r < 16; ++r)
    for (int d = 0; d < 3; ++d) coefficients(r, d) = c(rng);
  const double fu = 2 + 2 * (c(rng) + 1), fv = 2 + 2 * (c(rng) + 1), phase = 3 * c(rng);
  StencilProblem p;
  p.net = ControlNet(m, n);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = double(i) / m, v = double(j) / n;
      Eigen::RowVector3d point(u, v, 0);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) point += 0.3 * std::pow(u, a) * std::pow(v, b) * coefficients.row(4 * a + b);
      point.z() += 0.4 * std::sin(fu * u + phase) * std::cos(fv * v);
      p.net.at(i, j) = point;
    }
  p.rings = 2;
  return p;
}

}  // namespace

TEST_CASE("StencilFamilyObjective: the analytic derivative equals central differences", "[alpha]") {
  const StencilProblem p = ribbon_problem(8, 7, 3);
  for (const char* name : {"thin_plate", "twist", "dirichlet", "e3", "thin_plate+0.3*e3"}) {
    StencilFamilyObjective f(p, objective_named(name), backend("eigen-ldlt"));
    for (double w : {0.05, 0.4, 0.9}) {
      const double h = 1e-5;
      const double fd = (f.evaluate(w + h).value - f.evaluate(w - h).value) / (2 * h);
      const auto e = f.evaluate(w);
      INFO(name << " at w = " << w);
      REQUIRE(e.ok());
      CHECK(e.has_derivative);
      CHECK(e.derivative == Approx(fd).epsilon(1e-6).margin(1e-9 * std::abs(e.value)));
    }
    CHECK(f.analyses() == 1);  // one symbolic analysis for every w
  }
}

TEST_CASE("StencilFamilyObjective: the net is the one solve_stencil_net gives for c1_family_stencil(w)", "[alpha]") {
  StencilProblem p = ribbon_problem(9, 6, 11);
  // far from the origin and large: the evaluator works in its normalised frame, the caller's units out
  p.net.points = (p.net.points * 1e3).rowwise() + Eigen::RowVector3d(5e4, -2e4, 7e3);
  StencilFamilyObjective f(p, objective_named("thin_plate"), backend("eigen-ldlt"));
  auto solver = solvers::make_solver("eigen-ldlt");
  for (double w : {0.0, 0.3, 1.0}) {
    const auto e = f.evaluate(w);
    REQUIRE(e.ok());
    const StencilSolveResult direct = solve_stencil_net(p, c1_family_stencil(w), *solver);
    REQUIRE(direct.summary.ok());
    CHECK(max_difference(e.net, direct.net) <= 1e-9 * 5e4);
    CHECK(e.value == Approx(combined_energy(direct.net, thin_plate_terms())).epsilon(1e-9));
  }
}

TEST_CASE("search_weight: equals Brent's minimiser on random ribbon problems", "[alpha]") {
  int interior = 0;
  std::uint32_t seed = 20;
  for (auto [m, n] : {std::pair{7, 7}, std::pair{9, 6}, std::pair{6, 10}, std::pair{8, 8}, std::pair{10, 7}}) {
    const StencilProblem p = ribbon_problem(m, n, seed++);
    for (const char* name : {"thin_plate", "twist", "dirichlet", "e3"}) {
      const Objective objective = objective_named(name);
      const AlphaSearchSummary s = search_weight(p, objective, backend("eigen-ldlt"));
      INFO(name << ", m = " << m << ", n = " << n << ": " << s.brief_report());
      REQUIRE((s.status == SearchStatus::kSuccess));
      REQUIRE(s.parameter);
      StencilFamilyObjective g(p, objective, backend("eigen-ldlt"));
      const auto brent =
          boost::math::tools::brent_find_minima([&](double w) { return g.evaluate(w, false).value; }, 0.0, 1.0, 40);
      CHECK(*s.parameter == Approx(brent.first).margin(1e-6));
      CHECK(s.value <= brent.second * (1 + 1e-12));
      CHECK(s.value == Approx(g.evaluate(*s.parameter, false).value).epsilon(1e-14));
      if (!s.at_bound) ++interior;
      CHECK(s.solves <= 2 * s.evaluations);
    }
  }
  CHECK(interior >= 3);  // the comparison covered interior optima, not only bounds
}

TEST_CASE("search_weight: an optimum on a bound is reported at_bound, with its outward slope", "[alpha]") {
  const StencilProblem p = ribbon_problem(8, 8, 23);
  // the thin plate energy of smooth ribbon data is least at the biharmonic end, w = 0
  StencilFamilyObjective f(p, objective_named("thin_plate"), backend("eigen-ldlt"));
  const AlphaSearchSummary s = search_weight(p, objective_named("thin_plate"), backend("eigen-ldlt"));
  INFO(s.brief_report());
  REQUIRE(s.status == SearchStatus::kSuccess);
  REQUIRE(s.parameter);
  CHECK(s.at_bound);
  CHECK_FALSE(s.flat);
  CHECK(*s.parameter == 0.0);
  CHECK(f.evaluate(0.0).derivative > 0);
  // e3's interior optimum (near 0.84) lies above [0.1, 0.5]: the search stops on the upper bound
  WeightSearchOptions narrow;
  narrow.search.lower = 0.1;
  narrow.search.upper = 0.5;
  const AlphaSearchSummary t = search_weight(p, objective_named("e3"), backend("eigen-ldlt"), narrow);
  INFO(t.brief_report());
  REQUIRE(t.status == SearchStatus::kSuccess);
  REQUIRE(t.parameter);
  CHECK(t.at_bound);
  CHECK(*t.parameter == 0.5);
  const AlphaSearchSummary full = search_weight(p, objective_named("e3"), backend("eigen-ldlt"));
  REQUIRE(full.parameter);
  CHECK_FALSE(full.at_bound);
  CHECK(*full.parameter > 0.5);
}

TEST_CASE("search_weight: bilinear data is flat, no optimum claimed", "[alpha]") {
  // every member of the family reproduces a bilinear net (δ⁴ and δ² annihilate linear data)
  StencilProblem p;
  p.net = make_bilinear_net(8, 7, 5);
  p.rings = 2;
  for (const char* name : {"thin_plate", "twist", "e3"}) {
    const AlphaSearchSummary s = search_weight(p, objective_named(name), backend("eigen-ldlt"));
    INFO(name << ": " << s.brief_report());
    CHECK(s.status == SearchStatus::kFlat);
    CHECK(s.flat);
    CHECK_FALSE(s.parameter);
    CHECK_FALSE(s.at_bound);
  }
}

TEST_CASE("search_weight: a problem with one data ring is refused as not applicable", "[alpha]") {
  StencilProblem p = ribbon_problem(7, 7, 4);
  p.rings = 1;
  const AlphaSearchSummary s = search_weight(p, objective_named("thin_plate"), backend("eigen-ldlt"));
  CHECK(s.status == SearchStatus::kNotApplicable);
  CHECK(std::string(to_string(s.status)) == "not_applicable");
  CHECK(s.message.rfind("rings: ", 0) == 0);
  CHECK_FALSE(s.parameter);
  CHECK(s.evaluations == 0);
  // bounds outside the family's [0, 1] and a backend without a matrix are refused too
  WeightSearchOptions wide;
  wide.search.upper = 1.5;
  std::string why;
  CHECK_FALSE(wide.is_valid(&why));
  p.rings = 2;
  CHECK(search_weight(p, objective_named("thin_plate"), backend("eigen-ldlt"), wide).status ==
        SearchStatus::kNotApplicable);
  CHECK(WeightSearchOptions{}.is_valid(nullptr));
  const AlphaSearchSummary no_matrix = search_weight(p, objective_named("thin_plate"), backend("gauss-seidel"));
  CHECK(no_matrix.status == SearchStatus::kNotApplicable);
  CHECK(no_matrix.message.rfind("solver: ", 0) == 0);
  CHECK(no_matrix.evaluations == 0);
}

namespace {

// A problem with one data ring and a free grid that holds a fixed block inside (a hole), from the
// smooth ribbon surface: the 3×3 family's problem class beyond the rectangle.
StencilProblem hole_problem(int m, int n, std::uint32_t seed) {
  StencilProblem p = ribbon_problem(m, n, seed);
  p.rings = 1;
  p.free = FreeGrid::Constant(m + 1, n + 1, false);
  for (int i = 1; i < m; ++i)
    for (int j = 1; j < n; ++j) p.free(i, j) = !(i >= m / 3 && i < m / 3 + 2 && j >= n / 3 && j < n / 3 + 2);
  return p;
}

}  // namespace

TEST_CASE("StencilFamilyObjective: the alpha family's analytic derivative equals central differences", "[alpha]") {
  for (const StencilProblem& p : {ribbon_problem(8, 7, 5), hole_problem(9, 8, 6)}) {
    for (const char* name : {"thin_plate", "twist", "e3"}) {
      StencilFamilyObjective f(p, objective_named(name), backend("eigen-ldlt"), {}, alpha_stencil_family());
      for (double a : {-0.2, -0.05, 0.1}) {
        const double h = 1e-5;
        const double fd = (f.evaluate(a + h).value - f.evaluate(a - h).value) / (2 * h);
        const auto e = f.evaluate(a);
        INFO(name << " at alpha = " << a << ", rings " << p.rings);
        REQUIRE(e.ok());
        CHECK(e.derivative == Approx(fd).epsilon(1e-6).margin(1e-9 * std::abs(e.value)));
      }
      CHECK(f.analyses() == 1);
    }
  }
}

TEST_CASE("search_alpha_on_problem: equals Brent's minimiser on two rings and on a free set with a hole", "[alpha]") {
  int interior = 0;
  std::uint32_t seed = 40;
  for (auto [m, n] : {std::pair{7, 7}, std::pair{9, 6}, std::pair{6, 10}, std::pair{10, 8}}) {
    for (const StencilProblem& p : {ribbon_problem(m, n, seed++), hole_problem(m, n, seed++)}) {
      for (const char* name : {"thin_plate", "twist", "e3"}) {
        const Objective objective = objective_named(name);
        const AlphaSearchSummary s = search_alpha_on_problem(p, objective, backend("eigen-ldlt"));
        INFO(name << ", m = " << m << ", n = " << n << ", rings " << p.rings << ": " << s.brief_report());
        REQUIRE((s.status == SearchStatus::kSuccess));
        REQUIRE(s.parameter);
        StencilFamilyObjective g(p, objective, backend("eigen-ldlt"), {}, alpha_stencil_family());
        const auto brent = boost::math::tools::brent_find_minima([&](double a) { return g.evaluate(a, false).value; },
                                                                 -0.25, 0.25, 40);
        CHECK(s.value <= brent.second * (1 + 1e-12));
        // Brent may stop in a worse local minimum (twist has two on some of these); where it
        // reaches the same value, it is at the same α
        if (brent.second <= s.value * (1 + 1e-9)) CHECK(*s.parameter == Approx(brent.first).margin(1e-6));
        if (!s.at_bound) ++interior;
      }
    }
  }
  CHECK(interior >= 3);  // interior optima were compared, not only bounds
}

TEST_CASE("search_alpha_on_problem: on the one-ring rectangle it finds search_alpha's optimum", "[alpha]") {
  for (auto [m, n] : {std::pair{6, 6}, std::pair{8, 5}}) {
    const Boundary b = make_smooth_boundary(m, n, 77);
    StencilProblem p = rings_problem(discrete_coons_net(b), 1);
    for (const char* name : {"thin_plate", "e3"}) {
      const AlphaSearchSummary s = search_alpha_on_problem(p, objective_named(name), backend("eigen-ldlt"));
      const AlphaSearchSummary t = search_alpha(b, objective_named(name), backend("eigen-ldlt"));
      INFO(name << ": " << s.brief_report() << " / " << t.brief_report());
      REQUIRE(s.parameter);
      REQUIRE(t.parameter);
      CHECK(*s.parameter == Approx(*t.parameter).margin(1e-6));
      CHECK(s.value == Approx(t.value).epsilon(1e-10));
    }
  }
}

TEST_CASE("search_alpha_on_problem: a grid backend or a problem the stencil leaves is refused, nothing evaluated",
          "[alpha]") {
  const StencilProblem p = hole_problem(8, 8, 3);
  const AlphaSearchSummary s = search_alpha_on_problem(p, objective_named("thin_plate"), backend("mg"));
  CHECK(s.status == SearchStatus::kNotApplicable);
  CHECK(s.evaluations == 0);
  StencilProblem bad = p;
  bad.free(0, 3) = true;  // a free point on the outer ring: its stencil leaves the net
  const AlphaSearchSummary t = search_alpha_on_problem(bad, objective_named("thin_plate"), backend("eigen-ldlt"));
  CHECK(t.status == SearchStatus::kNotApplicable);
  CHECK(t.evaluations == 0);
  CHECK_THAT(t.message, Catch::StartsWith("free"));
}

TEST_CASE("search_weight, search_alpha_on_problem: gmres, which also takes a matrix, finds the direct optimum",
          "[alpha]") {
  // gmres is a grid-stencil backend that falls back to ILUT on a matrix: it was refused as one that
  // cannot solve from the matrix, while mg (the grid only) still is (test above)
  REQUIRE(coons::solvers::accepts_matrix(backend("gmres")));
  REQUIRE_FALSE(coons::solvers::accepts_matrix(backend("mg")));
  coons::solvers::SolverOptions tight;
  tight.tolerance = 1e-13;
  const StencilProblem ribbons = ribbon_problem(8, 7, 40);
  const AlphaSearchSummary direct = search_weight(ribbons, objective_named("e3"), backend("eigen-ldlt"));
  const AlphaSearchSummary krylov = search_weight(ribbons, objective_named("e3"), backend("gmres"), {}, tight);
  INFO(direct.brief_report() << " / " << krylov.brief_report());
  REQUIRE((krylov.status == SearchStatus::kSuccess));
  REQUIRE((direct.status == SearchStatus::kSuccess));
  CHECK(*krylov.parameter == Approx(*direct.parameter).margin(1e-6));
  const StencilProblem hole = hole_problem(8, 8, 3);
  const AlphaSearchSummary a = search_alpha_on_problem(hole, objective_named("thin_plate"), backend("eigen-ldlt"));
  const AlphaSearchSummary b =
      search_alpha_on_problem(hole, objective_named("thin_plate"), backend("gmres"), {}, tight);
  INFO(a.brief_report() << " / " << b.brief_report());
  REQUIRE((b.status == SearchStatus::kSuccess));
  CHECK(*b.parameter == Approx(*a.parameter).margin(1e-6));
}

TEST_CASE("search_weight: a constant net is flat for every objective (no rounding noise read as an optimum)",
          "[alpha]") {
  // every point (0.1, 0.2, 0.3): the net is the same for every w; its coordinates' rounding is
  // no signal
  StencilProblem p;
  p.net = ControlNet(4, 4);
  p.net.points.rowwise() = Eigen::RowVector3d(0.1, 0.2, 0.3);
  p.rings = 2;
  for (const char* name : {"thin_plate", "twist", "dirichlet", "e3", "discrete_thin_plate"}) {
    const AlphaSearchSummary s = search_weight(p, objective_named(name), backend("eigen-ldlt"));
    INFO(name << ": " << s.brief_report());
    CHECK(s.status == SearchStatus::kFlat);
    CHECK_FALSE(s.at_bound);
    CHECK(s.value == 0);
  }
}

namespace {

// The α > 1/4 closest to 0.3 at which the α family's system on `p` is singular: A(α) = A₀ + α·A₁
// (affine in α), so the singular α are the real eigenvalues of the pencil A₀ v = −α A₁ v.
double singular_alpha(const StencilProblem& p) {
  const Eigen::MatrixXd a0 = Eigen::MatrixXd(assemble_stencil_system(p, alpha_stencil(alpha_mask(0))).A);
  const Eigen::MatrixXd a1 = Eigen::MatrixXd(assemble_stencil_system(p, alpha_stencil(alpha_mask(1))).A) - a0;
  Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> pencil(a0, -a1);
  double best = HUGE_VAL;
  for (Eigen::Index k = 0; k < a0.rows(); ++k) {
    if (!(std::abs(pencil.betas()(k)) > 1e-12) || std::abs(pencil.alphas()(k).imag()) > 1e-9) continue;
    const double alpha = pencil.alphas()(k).real() / pencil.betas()(k);
    if (alpha > 0.26 && std::abs(alpha - 0.3) < std::abs(best - 0.3)) best = alpha;
  }
  return best;
}

}  // namespace

TEST_CASE("StencilFamilyObjective: a near-singular alpha outside the definite interval is refused as singular",
          "[alpha]") {
  for (const StencilProblem& p : {ribbon_problem(8, 7, 5), hole_problem(9, 8, 6)}) {
    const double star = singular_alpha(p);
    REQUIRE(star < 1);
    StencilFamilyObjective f(p, objective_named("thin_plate"), backend("eigen-lu"), {}, alpha_stencil_family());
    INFO("rings " << p.rings << ", singular alpha " << star);
    const auto near = f.evaluate(star + 1e-9);
    CHECK_FALSE(near.ok());
    CHECK(near.summary.status == solvers::SolveStatus::kSingular);
    CHECK_THAT(near.summary.message, Catch::Contains("min|eigenvalue|/max|eigenvalue|"));
    CHECK(f.evaluate(star + 1e-3).ok());  // a regular system nearby is evaluated
  }
}

TEST_CASE(
    "search_alpha_on_problem: a near-singular alpha outside the definite interval is a failed evaluation and never "
    "the optimum",
    "[alpha]") {
  // two data rings and a free set with a hole: no closed form for the eigenvalues; the scan's
  // lower bound lies 1e-9 above a singular α
  for (const StencilProblem& p : {ribbon_problem(8, 7, 5), hole_problem(9, 8, 6)}) {
    const double star = singular_alpha(p);
    AlphaSearchOptions options;
    options.lower = star + 1e-9;
    options.upper = star + 0.05;
    const AlphaSearchSummary s =
        search_alpha_on_problem(p, objective_named("thin_plate"), backend("eigen-lu"), options);
    INFO("rings " << p.rings << ", singular alpha " << star << ": " << s.brief_report());
    test::check_refused_near_singular(s, options, star);
    if (s.status != SearchStatus::kSuccess) CHECK(s.status == SearchStatus::kFailedRegion);
  }
}
