#include "coons/surfaces/bspline_energy.h"

#include <catch2/catch.hpp>

#include "coons/metrics/energies.h"
#include "coons/net/quadrature.h"
#include "coons/surfaces/bspline_sampling.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// ∫∫ ‖∂^a_u ∂^b_v s‖² by Gauss–Legendre (coons/net/quadrature.h, `nodes` per knot span and
// direction) of evaluate_derivative: independent of the Gram matrices.
double quadrature_energy(const BSplineSurface& s, int a, int b, int nodes) {
  const QuadratureRule rule = gauss_legendre(nodes);
  const auto spans = [](const Eigen::VectorXd& knots) {
    std::vector<std::pair<double, double>> out;
    for (Eigen::Index k = 0; k + 1 < knots.size(); ++k)
      if (knots(k + 1) > knots(k)) out.emplace_back(knots(k), knots(k + 1));
    return out;
  };
  double sum = 0;
  for (const auto& [u0, u1] : spans(s.knots_u))
    for (const auto& [v0, v1] : spans(s.knots_v))
      for (Eigen::Index g = 0; g < rule.nodes.size(); ++g)
        for (Eigen::Index h = 0; h < rule.nodes.size(); ++h) {
          const double u = u0 + (u1 - u0) * rule.nodes(g), v = v0 + (v1 - v0) * rule.nodes(h);
          // From the left of the span's right end: evaluate inside the span.
          sum += (u1 - u0) * (v1 - v0) * rule.weights(g) * rule.weights(h) *
                 evaluate_derivative(s, a, b, u, v).squaredNorm();
        }
  return sum;
}

}  // namespace

TEST_CASE("bspline_energy: on Bézier knot vectors equals the Bernstein Gram energies of docs/math.md §5",
          "[surfaces][bspline]") {
  for (const auto& [m, n] : {std::pair{3, 5}, std::pair{4, 2}, std::pair{1, 3}}) {
    BSplineSurface s;
    s.degree_u = m;
    s.degree_v = n;
    s.knots_u = bezier_knots(m);
    s.knots_v = bezier_knots(n);
    s.net = make_random_net(m, n, std::uint32_t(10 * m + n));
    for (int a = 0; a <= 3; ++a)
      for (int b = 0; b + a <= 3; ++b) {
        INFO("m = " << m << ", n = " << n << ", E(" << a << ", " << b << ")");
        CHECK(bspline_energy(s, a, b) == Approx(surface_energy(s.net, a, b)).epsilon(1e-11).margin(1e-12));
      }
  }
}

TEST_CASE("bspline_energy: equals Gauss–Legendre quadrature on non-uniform knots", "[surfaces][bspline]") {
  for (int p = 1; p <= 5; ++p) {
    const int q = 6 - p;
    const BSplineSurface s = make_random_bspline_surface(p, p + 4, q, q + 3, std::uint32_t(50 + p));
    for (int a = 0; a <= 3; ++a)
      for (int b = 0; a + b <= 3; ++b) {
        INFO("p = " << p << ", q = " << q << ", E(" << a << ", " << b << ")");
        const double reference = quadrature_energy(s, a, b, 8);
        CHECK(bspline_energy(s, a, b) == Approx(reference).epsilon(1e-11).margin(1e-11));
      }
    CHECK(bspline_combined_energy(s, bspline_thin_plate_terms()) ==
          Approx(quadrature_energy(s, 2, 0, 8) + 2 * quadrature_energy(s, 1, 1, 8) + quadrature_energy(s, 0, 2, 8))
              .epsilon(1e-11)
              .margin(1e-11));
  }
}

TEST_CASE("bspline_derivative_points: its B-spline on the inner knots has the values of the derivative",
          "[surfaces][bspline]") {
  // Random knots repeat interior values (up to p times), so some derivative functions have an
  // empty support: their coefficients are 0 and the derivative is still exact on every span.
  for (int p = 1; p <= 5; ++p) {
    const BSplineSurface s = make_random_bspline_surface(p, p + 6, 2, 4, std::uint32_t(70 + p));
    Eigen::MatrixXd X(s.net.m + 1, s.net.n + 1);
    for (int i = 0; i <= s.net.m; ++i)
      for (int j = 0; j <= s.net.n; ++j) X(i, j) = s.net.at(i, j)(0);
    for (int a = 0; a <= p; ++a) {
      const Eigen::MatrixXd P = bspline_derivative_points(s.knots_u, p, X, a);
      REQUIRE(P.rows() == X.rows() - a);
      const Eigen::VectorXd inner = s.knots_u.segment(a, s.knots_u.size() - 2 * a);
      for (const double u : {0.0, 0.137, 0.5, 0.61, 0.999}) {
        const int span = find_span(inner, p - a, u);
        const Eigen::MatrixXd N = basis_derivatives(inner, p - a, span, u, 0);
        double value = 0;
        for (int r = 0; r <= p - a; ++r) value += N(0, r) * P(span - (p - a) + r, 2);
        // the a-th derivative of column 2 from the basis derivatives (A2.3) on the full knots
        const int full_span = find_span(s.knots_u, p, u);
        const Eigen::MatrixXd D = basis_derivatives(s.knots_u, p, full_span, u, a);
        double reference = 0;
        for (int r = 0; r <= p; ++r) reference += D(a, r) * X(full_span - p + r, 2);
        INFO("p = " << p << ", a = " << a << ", u = " << u);
        CHECK(value == Approx(reference).epsilon(1e-10).margin(1e-10));
      }
    }
    CHECK(bspline_derivative_points(s.knots_u, p, X, p + 1).rows() == 0);
  }
}

TEST_CASE("bspline_energy: a net F(u) + G(v) far from the origin has twist and E3 of rounding size, never below 0",
          "[surfaces][bspline]") {
  // Its exact twist and mixed derivatives vanish. The Gram products of the raw net lost them to
  // cancellation: at 1e6 the twist came out 0.149 and E3 785, beside a Dirichlet energy of 7e13.
  BSplineSurface s = make_random_bspline_surface(2, 6, 2, 6, 301);
  const BSplineSurface g = make_random_bspline_surface(2, 6, 2, 6, 302);
  for (int i = 0; i <= s.net.m; ++i)
    for (int j = 0; j <= s.net.n; ++j)
      s.net.at(i, j) = 1e6 * (Eigen::RowVector3d(3, -2, 5) + g.net.at(i, 0) + g.net.at(0, j));
  const double dirichlet = bspline_combined_energy(s, bspline_dirichlet_terms());
  REQUIRE(dirichlet > 1e11);
  for (const auto& terms : {bspline_twist_terms(), bspline_e3_terms()}) {
    const double e = bspline_combined_energy(s, terms);
    CHECK(e >= 0.0);
    CHECK(e <= 1e-20 * dirichlet);
  }
  for (int a = 0; a <= 2; ++a)
    for (int b = 0; b <= 2; ++b) CHECK(bspline_energy(s, a, b) >= 0.0);
}

TEST_CASE("bspline_energy_form: polarises the energy", "[surfaces][bspline]") {
  const BSplineSurface s = make_random_bspline_surface(3, 7, 2, 5, 81);
  const ControlNet Y = make_random_net(6, 4, 82);
  BSplineSurface moved = s;
  moved.net.points += 0.5 * Y.points;
  for (const auto& [a, b] : {std::pair{1, 1}, std::pair{2, 0}, std::pair{0, 1}})
    CHECK(bspline_energy(moved, a, b) ==
          Approx(bspline_energy(s, a, b) + 2 * 0.5 * bspline_energy_form(s, s.net, Y, a, b) +
                 0.25 * bspline_energy_form(s, Y, Y, a, b))
              .epsilon(1e-12));
}

TEST_CASE("sample_bspline_grid: points are the surface, derivatives match central differences", "[surfaces][bspline]") {
  BSplineSurface s = make_random_bspline_surface(3, 6, 2, 5, 91);
  s.knots_u = s.knots_u * 2.0 + Eigen::VectorXd::Constant(s.knots_u.size(), 1.0);  // domain [1, 3]
  const SurfaceSamples samples = sample_bspline_grid(s, 5);
  CHECK((samples.points.row(2 * 5 + 3) - evaluate(s, 1.0 + 2.0 * 0.5, 0.75)).norm() < 1e-14);
  const double h = 1e-5, u = 0.31, v = 0.63;
  const SurfacePoint p = bspline_surface_point(s, u, v);
  const Eigen::RowVector3d du = (bspline_surface_point(s, u + h, v).p - bspline_surface_point(s, u - h, v).p) / (2 * h);
  const Eigen::RowVector3d dv = (bspline_surface_point(s, u, v + h).p - bspline_surface_point(s, u, v - h).p) / (2 * h);
  const Eigen::RowVector3d duv =
      (bspline_surface_point(s, u, v + h).du - bspline_surface_point(s, u, v - h).du) / (2 * h);
  CHECK((p.du - du).norm() < 1e-6);
  CHECK((p.dv - dv).norm() < 1e-6);
  CHECK((p.duv - duv).norm() < 1e-5);
  CHECK(samples.twist.allFinite());
}

TEST_CASE("bspline_energy: a span of 1e-9 far from 0 is integrated as exactly as one at 0", "[surfaces][bspline]") {
  // The energies do not change when every knot moves by the same amount. Nodes placed at
  // 0.7 + 1e-9·x round to ulp(0.7), 5e-8 of the span: the energies moved by 1e-7 (review, exact
  // reference in Fractions); at 0 the nodes are exact.
  BSplineSurface at_07;
  at_07.degree_u = 3;
  at_07.degree_v = 2;
  at_07.knots_u = (Eigen::VectorXd(12) << 0, 0, 0, 0, 0.7, 0.7, 0.7, 0.70000000101, 1, 1, 1, 1).finished();
  at_07.knots_v = (Eigen::VectorXd(7) << 0, 0, 0, 0.5, 1, 1, 1).finished();
  at_07.net = make_random_net(7, 3, 5);
  BSplineSurface at_0 = at_07;
  at_0.knots_u = (at_07.knots_u.array() - 0.7).matrix();  // 0.70000000101 − 0.7 is exact (Sterbenz)
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; a + b <= 3; ++b) {
      INFO("E(" << a << ", " << b << ")");
      CHECK(bspline_energy(at_07, a, b) == Approx(bspline_energy(at_0, a, b)).epsilon(1e-12));
    }
}
