#include "coons/surfaces/bspline_surface.h"

#include <catch2/catch.hpp>
#include <random>

#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The largest distance, on a 41 × 41 grid of [0, 1]², between the surface (over its own domain)
// and the continuous bilinearly blended Coons patch of the boundary.
double distance_to_coons_patch(const BSplineSurface& s, const BSplineBoundary& b) {
  double worst = 0;
  const double u0 = s.knots_u(0), u1 = s.knots_u(s.knots_u.size() - 1);
  const double v0 = s.knots_v(0), v1 = s.knots_v(s.knots_v.size() - 1);
  for (int a = 0; a <= 40; ++a)
    for (int c = 0; c <= 40; ++c) {
      const double u = a / 40.0, v = c / 40.0;
      const Eigen::RowVector3d p = evaluate(s, u0 + u * (u1 - u0), v0 + v * (v1 - v0));
      worst = std::max(worst, (p - coons_patch_point(b, u, v)).norm());
    }
  return worst;
}

}  // namespace

TEST_CASE("evaluate (B-spline surface): equals the curve of curves", "[surfaces][bspline]") {
  for (int p = 1; p <= 4; ++p)
    for (int q = 1; q <= 4; ++q) {
      const BSplineSurface s =
          make_random_bspline_surface(p, p + 3 + q, q, q + 2 + p, 4100U + 10U * p + q, 0.0, 2.0, -1.0, 1.0);
      REQUIRE(s.is_valid(nullptr));
      const int count_u = s.net.m + 1, count_v = s.net.n + 1;
      for (int k = 0; k <= 12; ++k)
        for (int l = 0; l <= 12; ++l) {
          const double u = 2.0 * k / 12.0, v = -1.0 + 2.0 * l / 12.0;
          // The v-curves of the rows of the net at v, then the u-curve through those points at u.
          Eigen::MatrixX3d column(count_u, 3);
          for (int i = 0; i < count_u; ++i) {
            Eigen::MatrixX3d row(count_v, 3);
            for (int j = 0; j < count_v; ++j) row.row(j) = s.net.at(i, j);
            column.row(i) = evaluate(BSplineCurve(q, s.knots_v, row), v);
          }
          const Eigen::RowVector3d expected = evaluate(BSplineCurve(p, s.knots_u, column), u);
          CHECK((evaluate(s, u, v) - expected).norm() < 1e-14);
        }
    }
}

TEST_CASE("evaluate (B-spline surface): on Bézier knot vectors equals the Bézier surface", "[surfaces][bspline]") {
  const ControlNet net = make_random_net(4, 3, 4300U);
  BSplineSurface s;
  s.degree_u = 4;
  s.degree_v = 3;
  s.knots_u = bezier_knots(4);
  s.knots_v = bezier_knots(3);
  s.net = net;
  for (int k = 0; k <= 10; ++k)
    for (int l = 0; l <= 10; ++l) {
      const double u = k / 10.0, v = l / 10.0;
      CHECK((evaluate(s, u, v) - evaluate(net, u, v)).norm() < 1e-14);
      CHECK((evaluate_derivative(s, 1, 1, u, v) - evaluate_derivative(net, 1, 1, u, v)).norm() < 1e-12);
      CHECK((evaluate_derivative(s, 2, 0, u, v) - evaluate_derivative(net, 2, 0, u, v)).norm() < 1e-11);
    }
}

TEST_CASE("evaluate_derivative (B-spline surface): partial derivatives match finite differences",
          "[surfaces][bspline]") {
  const BSplineSurface s = make_random_bspline_surface(3, 8, 2, 7, 4500U, 0.0, 2.0, -1.0, 1.0);
  const double h = 1e-5;
  std::mt19937 rng(4501U);
  std::uniform_real_distribution<double> U(0.05, 1.95), V(-0.95, 0.95);
  for (int k = 0; k < 40; ++k) {
    const double u = U(rng), v = V(rng);
    const Eigen::RowVector3d du = (evaluate(s, u + h, v) - evaluate(s, u - h, v)) / (2 * h);
    const Eigen::RowVector3d dv = (evaluate(s, u, v + h) - evaluate(s, u, v - h)) / (2 * h);
    const Eigen::RowVector3d duv =
        (evaluate_derivative(s, 1, 0, u, v + h) - evaluate_derivative(s, 1, 0, u, v - h)) / (2 * h);
    // Knots lie on a grid of step 2/40 (u) and 2/36 (v); a difference across one is not checked.
    const auto near_knot = [&](const Eigen::VectorXd& knots, double t) {
      return (knots.array() - t).abs().minCoeff() < 2 * h;
    };
    if (near_knot(s.knots_u, u) || near_knot(s.knots_v, v)) continue;
    CHECK((evaluate_derivative(s, 1, 0, u, v) - du).norm() < 1e-6 * (1 + du.norm()));
    CHECK((evaluate_derivative(s, 0, 1, u, v) - dv).norm() < 1e-6 * (1 + dv.norm()));
    CHECK((evaluate_derivative(s, 1, 1, u, v) - duv).norm() < 1e-5 * (1 + duv.norm()));
  }
}

TEST_CASE("compatible_boundary: opposite sides share degree and knots and stay the same curves",
          "[surfaces][bspline]") {
  const BSplineBoundary b = make_random_bspline_boundary(2, 7, 3, 6, 4700U);
  std::vector<CompatibilityNote> notes;
  const BSplineBoundary c = compatible_boundary(b, &notes);
  CHECK(c.bottom.degree == 3);
  CHECK(c.top.degree == 3);
  CHECK(c.bottom.knots == c.top.knots);
  CHECK(c.left.knots == c.right.knots);
  CHECK(c.left.degree == 3);
  for (const BSplineCurve* curve : {&c.bottom, &c.top, &c.left, &c.right}) {
    CHECK(curve->start() == 0.0);
    CHECK(curve->end() == 1.0);
    CHECK(knot_vector_problems(curve->knots, curve->degree, curve->count()).empty());
  }
  const std::pair<const BSplineCurve*, const BSplineCurve*> sides[] = {
      {&b.bottom, &c.bottom}, {&b.top, &c.top}, {&b.left, &c.left}, {&b.right, &c.right}};
  for (const auto& [before, after] : sides)
    for (int k = 0; k <= 200; ++k) {
      const double s = k / 200.0;
      const double t = before->start() + s * (before->end() - before->start());
      CHECK((evaluate(*before, t) - evaluate(*after, s)).norm() < 1e-13);
    }
  // bottom was raised from 2 to 3; every side received knots of its opposite side.
  REQUIRE(notes.size() == 4);
  CHECK(notes[0].side == "bottom");
  CHECK(notes[0].degree_raised_by == 1);
  CHECK(notes[1].degree_raised_by == 0);
  for (const CompatibilityNote& n : notes) CHECK(n.knots_inserted > 0);
}

TEST_CASE("compatible_boundary: knots of opposite sides a rounding error apart are one knot", "[surfaces][bspline]") {
  // bottom over [0, 0.3] with a knot at 0.1, top over [0, 1] with one at 1/3: reparametrised,
  // 0.1 / 0.3 = 0.33333333333333337 is one ulp from 1/3 = 0.3333333333333333.
  BSplineBoundary b = make_random_bspline_boundary(3, 6, 2, 4, 4800U);
  b.bottom.knots = (Eigen::VectorXd(10) << 0, 0, 0, 0, 0.06, 0.1, 0.3, 0.3, 0.3, 0.3).finished();
  b.top = BSplineCurve(3, (Eigen::VectorXd(10) << 0, 0, 0, 0, 0.2, 1.0 / 3.0, 1, 1, 1, 1).finished(),
                       b.bottom.points.rowwise() + Eigen::RowVector3d(0, 1, 0));
  REQUIRE(0.1 / 0.3 != 1.0 / 3.0);
  std::vector<CompatibilityNote> notes;
  const BSplineBoundary c = compatible_boundary(b, &notes);
  CHECK(c.bottom.knots == c.top.knots);
  CHECK(c.bottom.knots.size() == 10);  // nothing inserted: the knots were the same
  for (const CompatibilityNote& n : notes) CHECK((n.side == "left" || n.side == "right"));
  CHECK_FALSE(merged_span_problem(c, 0).has_value());
  // The curves moved by the rounding error only.
  for (int k = 0; k <= 100; ++k) {
    const double s = k / 100.0;
    CHECK((evaluate(b.bottom, 0.3 * s) - evaluate(c.bottom, s)).norm() < 1e-13);
    CHECK((evaluate(b.top, s) - evaluate(c.top, s)).norm() < 1e-13);
  }
}

TEST_CASE("merged_span_problem: two sides' knots closer than kMinKnotSpan but not the same are named",
          "[surfaces][bspline]") {
  BSplineBoundary b = make_random_bspline_boundary(3, 6, 2, 4, 4900U);
  b.left.knots = (Eigen::VectorXd(7) << 0, 0, 0, 0.5, 1, 1, 1).finished();
  for (const double gap : {1e-11, 1e-10}) {
    INFO("gap " << gap);
    b.right.knots = (Eigen::VectorXd(7) << 0, 0, 0, 0.5 + gap, 1, 1, 1).finished();
    const BSplineBoundary c = compatible_boundary(b);
    CHECK_FALSE(merged_span_problem(c, 0).has_value());
    const auto why = merged_span_problem(c, 1);
    REQUIRE(why.has_value());
    CHECK(why->find("left and right") != std::string::npos);
  }
  b.right.knots = (Eigen::VectorXd(7) << 0, 0, 0, 0.5 + 1e-8, 1, 1, 1).finished();
  CHECK_FALSE(merged_span_problem(compatible_boundary(b), 1).has_value());
}

TEST_CASE("greville_coons_surface: equals the continuous bilinearly blended Coons patch of its B-spline curves",
          "[surfaces][bspline]") {
  int cases = 0;
  for (int p = 1; p <= 5; ++p)
    for (int q = 1; q <= 5; ++q)
      for (int extra : {0, 3, 9}) {
        const std::uint32_t seed = 5000U + 100U * p + 10U * q + extra;
        const BSplineBoundary b = make_random_bspline_boundary(p, p + 1 + extra, q, q + 2 + extra / 2, seed);
        const BSplineSurface s = greville_coons_surface(compatible_boundary(b));
        INFO("p = " << p << ", q = " << q << ", extra = " << extra);
        REQUIRE(s.is_valid(nullptr));
        CHECK(distance_to_coons_patch(s, b) < 1e-12);
        ++cases;
      }
  CHECK(cases == 75);
}

TEST_CASE("greville_coons_surface: on Bézier knot vectors is the discrete Coons net of docs/math.md §2",
          "[surfaces][bspline]") {
  const Boundary frame = make_random_boundary(5, 3, 5100U);
  const BSplineBoundary b{BSplineCurve(5, bezier_knots(5), frame.bottom), BSplineCurve(5, bezier_knots(5), frame.top),
                          BSplineCurve(3, bezier_knots(3), frame.left), BSplineCurve(3, bezier_knots(3), frame.right)};
  const BSplineSurface s = greville_coons_surface(b);
  CHECK(max_difference(s.net, discrete_coons_net(frame)) < 1e-15);
}

TEST_CASE("greville_coons_surface: interpolates the boundary and reproduces bilinear patches", "[surfaces][bspline]") {
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 9, 2, 8, 5300U));
  const BSplineSurface s = greville_coons_surface(b);
  const BSplineBoundary edges = boundary_of(s);
  CHECK(edges.bottom.points == b.bottom.points);
  CHECK(edges.top.points == b.top.points);
  CHECK(edges.left.points == b.left.points);
  CHECK(edges.right.points == b.right.points);
  // Four straight sides of a bilinear patch, with non-uniform knots: the net lies on that patch at
  // the Greville abscissae, and the surface is the bilinear patch.
  const Eigen::RowVector3d c00(0, 0, 0), c10(2, 0, 1), c01(0, 3, -1), c11(2, 3, 2);
  const auto bilinear = [&](double u, double v) -> Eigen::RowVector3d {
    return (1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + (1 - u) * v * c01 + u * v * c11;
  };
  BSplineBoundary lines = b;
  const Eigen::VectorXd xi = greville_abscissae(b.bottom), eta = greville_abscissae(b.left);
  for (Eigen::Index i = 0; i < xi.size(); ++i) {
    lines.bottom.points.row(i) = bilinear(xi(i), 0);
    lines.top.points.row(i) = bilinear(xi(i), 1);
  }
  for (Eigen::Index j = 0; j < eta.size(); ++j) {
    lines.left.points.row(j) = bilinear(0, eta(j));
    lines.right.points.row(j) = bilinear(1, eta(j));
  }
  const BSplineSurface flat = greville_coons_surface(lines);
  for (int k = 0; k <= 20; ++k)
    for (int l = 0; l <= 20; ++l)
      CHECK((evaluate(flat, k / 20.0, l / 20.0) - bilinear(k / 20.0, l / 20.0)).norm() < 1e-14);
}

TEST_CASE("greville_coons_surface: the uniform weights i/(N−1) miss the Coons patch on non-uniform knots",
          "[surfaces][bspline]") {
  // The trap of issue 12 (OpenCASCADE's stretch weighting of B-spline poles): the same Boolean sum
  // with the weights 1 − i/(N−1) instead of the Greville abscissae is another surface.
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 10, 3, 9, 5500U));
  BSplineSurface uniform = greville_coons_surface(b);
  Boundary frame = boundary_of(uniform.net);
  uniform.net = discrete_coons_net(frame);
  CHECK(distance_to_coons_patch(greville_coons_surface(b), b) < 1e-12);
  CHECK(distance_to_coons_patch(uniform, b) > 1e-3);
}
