#include "coons/surfaces/bspline_energy.h"

#include <catch2/catch.hpp>

#include "coons/metrics/energies.h"
#include "coons/metrics/quadrature.h"
#include "coons/surfaces/bspline_sampling.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// ∫∫ ‖∂^a_u ∂^b_v s‖² by Gauss–Legendre (coons/metrics/quadrature.h, `nodes` per knot span and
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

TEST_CASE("bspline_gram: G^0 rows sum to the integrals (u_{i+p+1} - u_i)/(p+1) of the basis functions",
          "[surfaces][bspline]") {
  for (int p = 1; p <= 5; ++p) {
    const Eigen::VectorXd knots = make_random_knots(p, p + 6, std::uint32_t(70 + p), -1.0, 2.0);
    const Eigen::MatrixXd G = bspline_gram(knots, p, 0);
    for (Eigen::Index i = 0; i < G.rows(); ++i)
      CHECK(G.row(i).sum() == Approx((knots(i + p + 1) - knots(i)) / (p + 1)).epsilon(1e-13));
    CHECK(bspline_gram(knots, p, p + 1).cwiseAbs().maxCoeff() == 0.0);
  }
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
