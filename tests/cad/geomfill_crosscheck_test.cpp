// Cross-check with OpenCASCADE's GeomFill_BSplineCurves (GeomFill_StretchStyle, GeomFill_CoonsStyle):
// the net it fills from four B-spline curves against coons' nets (docs/cad.md, "Cross-check").
// Bézier (single-span, uniform) boundaries: Stretch equals the discrete Coons net. Non-uniform
// knots: Stretch weights the poles by i/(N−1), not by the Greville abscissae, and differs from the
// continuous Coons patch; coons' Greville net is that patch (checked by evaluating OpenCASCADE's
// own curves and surface). The measured numbers are printed (WARN) for docs/cad.md.
#include <GeomFill_BSplineCurves.hxx>
#include <Standard_Failure.hxx>
#include <algorithm>
#include <catch2/catch.hpp>
#include <stdexcept>

#include "coons/cad/occt_convert.h"
#include "coons/net/coons_net.h"
#include "support/bspline_fixtures.h"

using namespace coons;

namespace {

// GeomFill's surface for bottom, right, top, left (a closed contour C1..C4 head to tail).
BSplineSurface geomfill(const BSplineBoundary& b, GeomFill_FillingStyle style) {
  auto reversed = [](const BSplineCurve& c) {
    Handle(Geom_BSplineCurve) r = cad::to_occt(c);
    r->Reverse();
    return r;
  };
  try {
    GeomFill_BSplineCurves fill(cad::to_occt(b.bottom), cad::to_occt(b.right), reversed(b.top), reversed(b.left),
                                style);
    return cad::from_occt(*fill.Surface());
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("GeomFill_BSplineCurves: ") + e.DynamicType()->Name() + ": " +
                             e.GetMessageString());
  }
}

// The largest pole difference, allowing GeomFill to have swapped u and v.
double net_difference(const BSplineSurface& a, const ControlNet& b) {
  double d = std::numeric_limits<double>::infinity();
  if (a.net.m == b.m && a.net.n == b.n) d = (a.net.points - b.points).cwiseAbs().maxCoeff();
  if (a.net.m == b.n && a.net.n == b.m) {
    double t = 0;
    for (int i = 0; i <= b.m; ++i)
      for (int j = 0; j <= b.n; ++j) t = std::max(t, (a.net.at(j, i) - b.at(i, j)).cwiseAbs().maxCoeff());
    d = std::min(d, t);
  }
  return d;
}

Boundary bezier_boundary(const BSplineBoundary& b) {
  Boundary out;
  out.m = b.bottom.count() - 1;
  out.n = b.left.count() - 1;
  out.bottom = b.bottom.points;
  out.top = b.top.points;
  out.left = b.left.points;
  out.right = b.right.points;
  return out;
}

BSplineBoundary random_bezier_boundary(int m, int n, std::uint32_t seed) {
  BSplineBoundary b = test::make_random_bspline_boundary(m, m + 1, n, n + 1, seed);
  // same degree on opposite sides: rebuild top and right as Bézier curves through the corners
  b.top = BSplineCurve(m, test::bezier_knots(m), test::make_random_bspline(m, m + 1, seed + 7).points);
  b.right = BSplineCurve(n, test::bezier_knots(n), test::make_random_bspline(n, n + 1, seed + 9).points);
  b.bottom = BSplineCurve(m, test::bezier_knots(m), b.bottom.points);
  b.left = BSplineCurve(n, test::bezier_knots(n), b.left.points);
  b.top.points.row(0) = b.left.points.row(n);
  b.right.points.row(0) = b.bottom.points.row(m);
  b.top.points.row(m) = b.right.points.row(n);
  b.left.points.row(0) = b.bottom.points.row(0);
  return b;
}

}  // namespace

TEST_CASE(
    "GeomFill_BSplineCurves: Stretch equals the discrete Coons net on Bezier boundaries, CoonsStyle the Hermite one",
    "[cad]") {
  double stretch = 0, coons_style = 0, coons_style_hermite = 0;
  int cases = 0;
  for (int m = 1; m <= 5; ++m)
    for (int n : {1, 2, 3, 5}) {
      const BSplineBoundary b = random_bezier_boundary(m, n, std::uint32_t(31 * m + n));
      const ControlNet coons = discrete_coons_net(bezier_boundary(b));
      stretch = std::max(stretch, net_difference(geomfill(b, GeomFill_StretchStyle), coons));
      // GeomFill refuses CoonsStyle below 4 poles a side ("invalid filling style")
      if (m >= 3 && n >= 3) {
        const BSplineSurface filled = geomfill(b, GeomFill_CoonsStyle);
        coons_style = std::max(coons_style, net_difference(filled, coons));
        coons_style_hermite =
            std::max(coons_style_hermite, net_difference(filled, hermite_coons_net(bezier_boundary(b))));
      }
      ++cases;
    }
  WARN("Bezier boundaries, " << cases << " degree pairs: max |GeomFill Stretch - discrete Coons net| = " << stretch
                             << ", max |GeomFill CoonsStyle - discrete Coons net| = " << coons_style
                             << ", max |GeomFill CoonsStyle - Hermite Coons net| = " << coons_style_hermite);
  CHECK(stretch <= 1e-14);
  CHECK(coons_style > 1e-3);            // CoonsStyle blends by cubic Hermite functions: another surface,
  CHECK(coons_style_hermite <= 1e-14);  // coons' hermite-coons net (docs/math.md §2)
}

TEST_CASE("GeomFill_BSplineCurves: non-uniform knots differ from the Greville net, which is the Coons patch", "[cad]") {
  double stretch_vs_greville = 0, greville_vs_patch = 0, stretch_vs_patch = 0;
  int cases = 0;
  for (int p = 1; p <= 5; ++p)
    for (int q : {1, 2, 4}) {
      const BSplineBoundary b =
          compatible_boundary(test::make_random_bspline_boundary(p, p + 4, q, q + 3, std::uint32_t(13 * p + q)));
      const BSplineSurface greville = greville_coons_surface(b);
      const BSplineSurface stretch = geomfill(b, GeomFill_StretchStyle);
      stretch_vs_greville = std::max(stretch_vs_greville, net_difference(stretch, greville.net));
      // the continuous bilinearly blended Coons patch of OpenCASCADE's own curves, at 21 × 21 points
      const Handle(Geom_BSplineCurve) B = cad::to_occt(b.bottom), T = cad::to_occt(b.top), L = cad::to_occt(b.left),
                                      R = cad::to_occt(b.right);
      const Handle(Geom_BSplineSurface) G = cad::to_occt(greville), S = cad::to_occt(stretch);
      const bool swapped = stretch.net.m != greville.net.m;
      for (int a = 0; a <= 20; ++a)
        for (int c = 0; c <= 20; ++c) {
          const double u = a / 20.0, v = c / 20.0;
          const gp_XYZ patch = (1 - v) * B->Value(u).XYZ() + v * T->Value(u).XYZ() + (1 - u) * L->Value(v).XYZ() +
                               u * R->Value(v).XYZ() -
                               ((1 - u) * (1 - v) * B->Value(0).XYZ() + u * (1 - v) * B->Value(1).XYZ() +
                                (1 - u) * v * T->Value(0).XYZ() + u * v * T->Value(1).XYZ());
          greville_vs_patch = std::max(greville_vs_patch, (G->Value(u, v).XYZ() - patch).Modulus());
          const gp_Pnt s = swapped ? S->Value(v, u) : S->Value(u, v);
          stretch_vs_patch = std::max(stretch_vs_patch, (s.XYZ() - patch).Modulus());
        }
      ++cases;
    }
  WARN("non-uniform knots, " << cases << " degree pairs: max pole |Stretch - Greville net| = " << stretch_vs_greville
                             << "; at 21x21 points: max |Greville surface - Coons patch| = " << greville_vs_patch
                             << ", max |Stretch surface - Coons patch| = " << stretch_vs_patch);
  CHECK(stretch_vs_greville > 1e-3);
  CHECK(stretch_vs_patch > 1e-3);
  CHECK(greville_vs_patch <= 1e-13);
}

namespace {

// Four sides on the knot vectors `ku` (bottom, top) and `kv` (left, right), random points with
// shared corners.
BSplineBoundary boundary_on_knots(int p, const Eigen::VectorXd& ku, int q, const Eigen::VectorXd& kv,
                                  std::uint32_t seed) {
  const int cu = int(ku.size()) - p - 1, cv = int(kv.size()) - q - 1;
  const auto side = [&](int degree, const Eigen::VectorXd& knots, int count, std::uint32_t s) {
    return BSplineCurve(degree, knots, test::make_random_bspline(degree, count, s).points);
  };
  BSplineBoundary b{side(p, ku, cu, seed), side(p, ku, cu, seed + 1), side(q, kv, cv, seed + 2),
                    side(q, kv, cv, seed + 3)};
  b.left.points.row(0) = b.bottom.points.row(0);
  b.right.points.row(0) = b.bottom.points.row(cu - 1);
  b.left.points.row(cv - 1) = b.top.points.row(0);
  b.right.points.row(cv - 1) = b.top.points.row(cu - 1);
  return b;
}

Eigen::VectorXd clamped_uniform_knots(int degree, int spans) {
  Eigen::VectorXd k(spans + 2 * degree + 1);
  for (Eigen::Index i = 0; i < k.size(); ++i) k(i) = std::clamp(double(i - degree), 0.0, double(spans)) / spans;
  return k;
}

}  // namespace

TEST_CASE("GeomFill_BSplineCurves: several spans with equally spaced Greville abscissae agree with Stretch", "[cad]") {
  // Equally spaced Greville abscissae on several spans: degree 1 on uniform knots, and degree 2
  // on 0 0 0 ½ ½ 1 1 1 (abscissae 0, ¼, ½, ¾, 1). There i/(N − 1) is the Greville weight.
  const Eigen::VectorXd quadratic = (Eigen::VectorXd(8) << 0, 0, 0, 0.5, 0.5, 1, 1, 1).finished();
  double equal_spacing = 0;
  for (std::uint32_t seed : {3U, 5U, 8U}) {
    const BSplineBoundary a = boundary_on_knots(1, clamped_uniform_knots(1, 6), 2, quadratic, seed);
    const BSplineBoundary b = boundary_on_knots(2, quadratic, 1, clamped_uniform_knots(1, 4), seed + 10);
    for (const BSplineBoundary* x : {&a, &b})
      equal_spacing =
          std::max(equal_spacing, net_difference(geomfill(*x, GeomFill_StretchStyle), greville_coons_surface(*x).net));
  }
  // Clamped uniform cubic knots on 5 spans: the abscissae bunch near the ends, so i/(N − 1) is not
  // the Greville weight and Stretch is another surface.
  double cubic = 0;
  for (std::uint32_t seed : {3U, 5U, 8U}) {
    const BSplineBoundary c = boundary_on_knots(3, clamped_uniform_knots(3, 5), 3, clamped_uniform_knots(3, 4), seed);
    cubic = std::max(cubic, net_difference(geomfill(c, GeomFill_StretchStyle), greville_coons_surface(c).net));
  }
  WARN("multi-span uniform knots: max pole |Stretch - Greville net| = "
       << equal_spacing << " (equally spaced abscissae), " << cubic << " (clamped uniform cubic)");
  CHECK(equal_spacing <= 1e-14);
  CHECK(cubic > 1e-3);
}
