// Properties of the Coons family: interpolation of the boundary data, exact Bézier nets, corner
// twists (LN1), and the compatibility conditions of the general Coons patch.
#include <catch2/catch.hpp>
#include <cmath>

#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/net/degree_elevation.h"
#include "coons/surfaces/surface.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using V = Eigen::RowVector3d;

namespace {

const double kT[] = {0.0, 0.1, 0.37, 0.5, 0.83, 1.0};
const double kPi2 = 9.869604401089358;  // π²

// The general Coons data of a Bézier surface: its boundary curves, the cross derivatives along
// them and its corner twists — compatible by construction.
GeneralCoonsData data_of(const ControlNet& net) {
  auto column = [&](const ControlNet& d, int i) {  // the curve in v at u-index i
    Eigen::MatrixX3d P(d.n + 1, 3);
    for (int j = 0; j <= d.n; ++j) P.row(j) = d.at(i, j);
    return BezierCurve(P);
  };
  auto row = [&](const ControlNet& d, int j) {  // the curve in u at v-index j
    Eigen::MatrixX3d P(d.m + 1, 3);
    for (int i = 0; i <= d.m; ++i) P.row(i) = d.at(i, j);
    return BezierCurve(P);
  };
  const ControlNet du = derivative_net(net, 1, 0), dv = derivative_net(net, 0, 1);
  const BoundaryCurves b{row(net, 0), row(net, net.n), column(net, 0), column(net, net.m)};
  std::array<V, 4> twist;
  for (int c = 0; c < 4; ++c) twist[c] = evaluate_derivative(net, 1, 1, c % 2, c < 2 ? 0.0 : 1.0);
  return GeneralCoonsData{b, column(du, 0), column(du, du.m), row(dv, 0), row(dv, dv.n), twist};
}

// A compatible general-Coons datum that is not polynomial: analytic curves of the surface
// z = sin(πu) sin(πv) + uv over the unit square.
GeneralCoonsData analytic_data() {
  return GeneralCoonsData{BoundaryCurves{AnalyticCurve({"u", "0", "0"}), AnalyticCurve({"u", "1", "u"}),
                                         AnalyticCurve({"0", "v", "0"}), AnalyticCurve({"1", "v", "v"})},
                          AnalyticCurve({"1", "0", "pi*sin(pi*v) + v"}),
                          AnalyticCurve({"1", "0", "-pi*sin(pi*v) + v"}),
                          AnalyticCurve({"0", "1", "pi*sin(pi*u) + u"}),
                          AnalyticCurve({"0", "1", "-pi*sin(pi*u) + u"}),
                          {V(0, 0, kPi2 + 1), V(0, 0, -kPi2 + 1), V(0, 0, -kPi2 + 1), V(0, 0, kPi2 + 1)}};
}

double boundary_error(const Surface& s, const BoundaryCurves& b) {
  double e = 0;
  for (double t : kT) {
    e = std::max(e, (s.at(t, 0) - b.bottom.at(t)).norm());
    e = std::max(e, (s.at(t, 1) - b.top.at(t)).norm());
    e = std::max(e, (s.at(0, t) - b.left.at(t)).norm());
    e = std::max(e, (s.at(1, t) - b.right.at(t)).norm());
  }
  return e;
}

double cross_derivative_error(const Surface& s, const GeneralCoonsData& g) {
  double e = 0;
  for (double t : kT) {
    e = std::max(e, (s.evaluate(0, t).du - g.du_left.at(t)).norm());
    e = std::max(e, (s.evaluate(1, t).du - g.du_right.at(t)).norm());
    e = std::max(e, (s.evaluate(t, 0).dv - g.dv_bottom.at(t)).norm());
    e = std::max(e, (s.evaluate(t, 1).dv - g.dv_top.at(t)).norm());
  }
  return e;
}

// max over a grid of |net surface − surface| for the point and every derivative up to order 2.
double net_error(const Surface& s, const ControlNet& net) {
  double e = 0;
  for (double u : kT)
    for (double v : kT) {
      const SurfacePoint p = s.evaluate(u, v);
      for (int a = 0; a <= 2; ++a)
        for (int b = 0; a + b <= 2; ++b)
          e = std::max(e, (evaluate_derivative(net, a, b, u, v) - p.derivative(a, b)).norm() /
                              std::max(1.0, p.derivative(a, b).norm()));
    }
  return e;
}

std::array<V, 4> random_vectors(std::uint32_t seed) {
  const BezierCurve c = make_random_bezier(3, seed);
  return {c.points.row(0), c.points.row(1), c.points.row(2), c.points.row(3)};
}

}  // namespace

TEST_CASE("Coons patches: every one reproduces its four boundary curves", "[surfaces]") {
  std::uint32_t seed = 1;
  for (auto [m, n] : {std::pair{1, 1}, {2, 5}, {3, 3}, {6, 2}}) {
    const BoundaryCurves b = make_random_boundary_curves(m, n, seed++);
    CHECK(boundary_error(make_coons(b, CoonsBlending::kLinear), b) < 1e-14);
    CHECK(boundary_error(make_coons(b, CoonsBlending::kHermite), b) < 1e-14);
  }
  // Analytic curves (LN4's ellipse arcs are in seed_examples_test).
  const GeneralCoonsData g = analytic_data();
  CHECK(boundary_error(make_coons(g.boundary, CoonsBlending::kLinear), g.boundary) < 1e-15);
  CHECK(boundary_error(make_coons(g.boundary, CoonsBlending::kHermite), g.boundary) < 1e-15);
  CHECK(boundary_error(make_general_coons(g), g.boundary) < 1e-15);
  // The Ferguson and 16-vector patches: their boundaries are the Ferguson cubics of the corner data.
  const HermitePatch h{random_vectors(5), random_vectors(6), random_vectors(7), random_vectors(8)};
  const BoundaryCurves cubics{Curve::hermite_cubic(h.corners[0], h.corners[1], h.du[0], h.du[1]),
                              Curve::hermite_cubic(h.corners[2], h.corners[3], h.du[2], h.du[3]),
                              Curve::hermite_cubic(h.corners[0], h.corners[2], h.dv[0], h.dv[2]),
                              Curve::hermite_cubic(h.corners[1], h.corners[3], h.dv[1], h.dv[3])};
  CHECK(boundary_error(make_hermite16(h), cubics) < 1e-14);
  CHECK(boundary_error(make_ferguson(h.corners, h.du, h.dv), cubics) < 1e-14);
}

TEST_CASE("general Coons patch: reproduces the curves and the cross derivatives it is given", "[surfaces]") {
  // Polynomial data from random Bézier surfaces of several degrees.
  std::uint32_t seed = 20;
  for (auto [m, n] : {std::pair{3, 3}, {4, 6}, {7, 2}}) {
    const ControlNet net = make_random_net(m, n, seed++);
    const GeneralCoonsData g = data_of(net);
    const Surface s = make_general_coons(g);
    CHECK(boundary_error(s, g.boundary) < 1e-13);
    CHECK(cross_derivative_error(s, g) < 1e-12);
    for (const auto& c : compatibility_conditions(g)) CHECK(c.gap < 1e-12);
  }
  // Analytic data (numerical derivatives).
  const GeneralCoonsData g = analytic_data();
  for (const auto& c : compatibility_conditions(g)) CHECK(c.gap < 1e-8);
  const Surface s = make_general_coons(g);
  CHECK(cross_derivative_error(s, g) < 1e-8);
}

TEST_CASE("general Coons patch: a surface of degree <= 3 in u or in v is reproduced from its own data", "[surfaces]") {
  // The Boolean sum reproduces whatever either cubic Hermite projector reproduces.
  for (auto [m, n] : {std::pair{3, 3}, {3, 7}, {5, 2}}) {
    const ControlNet net = make_random_net(m, n, 40 + m + n);
    const Surface s = make_general_coons(data_of(net));
    CHECK(max_distance([&](double u, double v) { return s.at(u, v); },
                       [&](double u, double v) { return evaluate(net, u, v); }) < 1e-13);
  }
}

TEST_CASE("bezier_net: the net of every polynomial surface evaluates to the surface (point and derivatives)",
          "[surfaces]") {
  const BoundaryCurves b = make_random_boundary_curves(4, 3, 11);
  const HermitePatch h{random_vectors(1), random_vectors(2), random_vectors(3), random_vectors(4)};
  Conoid oblique{make_random_bezier(3, 12), V(0.1, 0.2, -0.3), V(1, 0.5, 0.2), V(0.8, 0.1, -0.3)};
  const std::vector<std::pair<std::string, Surface>> surfaces = {
      {"ruled", make_ruled(make_random_bezier(2, 13), make_random_bezier(5, 14))},
      {"sectorial", make_sectorial(make_random_bezier(4, 15), V(0, 0, 2))},
      {"bilinear", make_bilinear(random_vectors(16))},
      {"oblique conoid", make_conoid(oblique)},
      {"parabolic conoid",
       make_conoid(
           right_conoid(BezierCurve((Eigen::MatrixX3d(3, 3) << -1, 0, 0, 0, 0, 2, 1, 0, 0).finished()), 2, 0.5))},
      {"bilinear-coons", make_coons(b, CoonsBlending::kLinear)},
      {"hermite-coons", make_coons(b, CoonsBlending::kHermite)},
      {"hermite-coons, degree 1", make_coons(make_random_boundary_curves(1, 2, 17), CoonsBlending::kHermite)},
      {"ferguson", make_ferguson(h.corners, h.du, h.dv)},
      {"hermite16", make_hermite16(h)},
      {"general-coons", make_general_coons(data_of(make_random_net(5, 4, 18)))},
  };
  for (const auto& [name, s] : surfaces) {
    INFO(name);
    const std::optional<ControlNet> net = s.bezier_net();
    REQUIRE(net);
    CHECK(net_error(s, *net) < 1e-12);
  }
  // Non-polynomial data has no exact net.
  CHECK_FALSE(make_general_coons(analytic_data()).bezier_net());
  CHECK_FALSE(make_conoid(right_helicoidal_conoid(1, 0, 6)).bezier_net());
}

TEST_CASE("bezier_net: the Coons patches of Bezier curves are the closed-form discrete nets (docs/math.md §2, §6)",
          "[surfaces]") {
  for (auto [m, n] : {std::pair{3, 3}, {5, 4}, {2, 6}}) {
    const BoundaryCurves b = make_random_boundary_curves(m, n, 50 + m * n);
    const ControlNet linear = *make_coons(b, CoonsBlending::kLinear).bezier_net();
    CHECK(max_difference(linear, discrete_coons_net(boundary_of(linear))) < 1e-14);
    const ControlNet hermite = *make_coons(b, CoonsBlending::kHermite).bezier_net();
    REQUIRE(hermite.m >= 3);
    REQUIRE(hermite.n >= 3);
    CHECK(max_difference(hermite, hermite_coons_net(boundary_of(hermite))) < 1e-14);
  }
}

TEST_CASE("bilinear Coons patch: the matrix form (1-u, -1, u) M (1-v, -1, v)^T = 0 (LN0, LN1)", "[surfaces]") {
  const BoundaryCurves b = make_random_boundary_curves(3, 4, 60);
  const Surface s = make_coons(b, CoonsBlending::kLinear);
  for (double u : kT)
    for (double v : kT) {
      const V M[3][3] = {{b.bottom.at(0), b.left.at(v), b.top.at(0)},
                         {b.bottom.at(u), s.at(u, v), b.top.at(u)},
                         {b.bottom.at(1), b.right.at(v), b.top.at(1)}};
      const double a[3] = {1 - u, -1, u}, c[3] = {1 - v, -1, v};
      V sum = V::Zero();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) sum += a[i] * c[j] * M[i][j];
      CHECK(sum.norm() < 1e-14);
    }
}

TEST_CASE("bilinear Coons patch: the twist at a corner is the difference of the boundary tangents", "[surfaces]") {
  // r_uv(i, j) = ±(top' − bottom')(i) ± (right' − left')(j) − (p00 − p10 − p01 + p11): at every
  // corner r_uv = [top'(i) − bottom'(i)] + [right'(j) − left'(j)] − (p00 − p10 − p01 + p11).
  for (std::uint32_t seed : {70u, 71u, 72u}) {
    const BoundaryCurves b = make_random_boundary_curves(3, 5, seed);
    const Surface s = make_coons(b, CoonsBlending::kLinear);
    const V corner_twist = b.bottom.at(0) - b.bottom.at(1) - b.top.at(0) + b.top.at(1);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const V expected = b.top.derivative(1, i) - b.bottom.derivative(1, i) + b.right.derivative(1, j) -
                           b.left.derivative(1, j) - corner_twist;
        CHECK((s.evaluate(i, j).duv - expected).norm() < 1e-13);
      }
    CHECK(s.evaluate(0, 0).duv.norm() > 1e-3);  // not zero in general
  }
}

TEST_CASE("bicubic Coons and Ferguson patches: zero twists at the four corners (LN1)", "[surfaces]") {
  const BoundaryCurves b = make_random_boundary_curves(4, 5, 80);
  const Surface coons = make_coons(b, CoonsBlending::kHermite);
  const HermitePatch h{random_vectors(81), random_vectors(82), random_vectors(83), random_vectors(84)};
  const Surface ferguson = make_ferguson(h.corners, h.du, h.dv);
  const Surface sixteen = make_hermite16(h);
  for (int c = 0; c < 4; ++c) {
    const double u = c % 2, v = c < 2 ? 0.0 : 1.0;
    CHECK(coons.evaluate(u, v).duv.norm() < 1e-13);
    CHECK(ferguson.evaluate(u, v).duv.norm() < 1e-13);
    // The 16-vector patch has the twists it is given, and its corner tangents.
    CHECK((sixteen.evaluate(u, v).duv - h.twist[c]).norm() < 1e-13);
    CHECK((sixteen.evaluate(u, v).du - h.du[c]).norm() < 1e-13);
    CHECK((sixteen.evaluate(u, v).dv - h.dv[c]).norm() < 1e-13);
  }
  // Away from the corners the Hermite-blended patch does twist.
  CHECK(coons.evaluate(0.5, 0.5).duv.norm() > 1e-3);
}

TEST_CASE("Ferguson patch: equals the bicubic Coons patch of its Ferguson-cubic boundaries (LN1)", "[surfaces]") {
  const HermitePatch h = ferguson_patch(random_vectors(90), random_vectors(91), random_vectors(92));
  const BoundaryCurves cubics{Curve::hermite_cubic(h.corners[0], h.corners[1], h.du[0], h.du[1]),
                              Curve::hermite_cubic(h.corners[2], h.corners[3], h.du[2], h.du[3]),
                              Curve::hermite_cubic(h.corners[0], h.corners[2], h.dv[0], h.dv[2]),
                              Curve::hermite_cubic(h.corners[1], h.corners[3], h.dv[1], h.dv[3])};
  const Surface ferguson = make_ferguson(h.corners, h.du, h.dv), coons = make_coons(cubics, CoonsBlending::kHermite);
  CHECK(max_difference(*ferguson.bezier_net(), *coons.bezier_net()) < 1e-14);
}

TEST_CASE("Hermite-blended Coons patch: cross derivatives blend the corner tangents (LN1, LN2)", "[surfaces]") {
  const BoundaryCurves b = make_random_boundary_curves(3, 4, 95);
  const Surface s = make_coons(b, CoonsBlending::kHermite);
  for (double v : kT) {
    const V expected = hermite(0, v) * b.bottom.derivative(1, 1) + hermite(1, v) * b.top.derivative(1, 1);
    CHECK((s.evaluate(1, v).du - expected).norm() < 1e-13);
  }
  // And the partially bicubic patch of (u, v, u² F0(v))'s boundary is that surface.
  const Surface p =
      make_coons(BoundaryCurves{AnalyticCurve({"u", "0", "u^2"}), AnalyticCurve({"u", "1", "0"}),
                                AnalyticCurve({"0", "v", "0"}), AnalyticCurve({"1", "v", "2*v^3 - 3*v^2 + 1"})},
                 CoonsBlending::kHermite);
  CHECK(max_distance([&](double u, double v) { return p.at(u, v); },
                     [](double u, double v) { return V(u, v, u * u * hermite(0, v)); }) < 1e-15);
}

TEST_CASE("compatibility_conditions: an incompatible datum shows at its corner and condition", "[surfaces]") {
  const GeneralCoonsData good = data_of(make_random_net(4, 4, 100));
  {
    GeneralCoonsData g = good;
    g.twist[3] += V(0, 0.5, 0);  // the top-right twist
    for (const auto& c : compatibility_conditions(g)) {
      INFO(c.condition);
      if (c.field == "twist[3]") {
        CHECK(c.corner == kCornerNames[3]);
        CHECK(c.gap == Approx(0.5));
      } else {
        CHECK(c.gap < 1e-12);
      }
    }
  }
  {
    GeneralCoonsData g = good;
    BezierCurve d = *g.du_left.bezier();
    d.points.row(0) += V(0.25, 0, 0);  // du_left(0) no longer bottom'(0); the twist at (0,0) changes too
    g.du_left = d;
    bool found = false;
    for (const auto& c : compatibility_conditions(g))
      if (c.condition == "du_left(0) = bottom'(0)") {
        found = true;
        CHECK(c.field == "du_left");
        CHECK(c.corner == kCornerNames[0]);
        CHECK(c.gap == Approx(0.25));
      }
    CHECK(found);
  }
  {
    GeneralCoonsData g = good;
    BezierCurve r = *g.boundary.right.bezier();
    r.points.row(r.degree()) += V(0, 0, 1e-3);  // right(1) no longer top(1)
    g.boundary.right = r;
    const auto conditions = compatibility_conditions(g);
    CHECK(conditions[3].field == "right");
    CHECK(conditions[3].corner == kCornerNames[3]);
    CHECK(conditions[3].gap == Approx(1e-3));
  }
}
