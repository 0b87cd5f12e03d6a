#include "coons/curves/analytic_curve.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/curves/bezier_fit.h"
#include "coons/curves/numerical_derivative.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {}

TEST_CASE("numerical_derivative: documented accuracy on smooth functions of unit scale", "[curves]") {
  // f(s) = (sin 3s, exp(s), s^5 - s^2): derivatives known in closed form.
  auto f = [](double s) { return Eigen::RowVector3d(std::sin(3 * s), std::exp(s), std::pow(s, 5) - s * s); };
  auto exact = [](int r, double s) -> Eigen::RowVector3d {
    switch (r) {
      case 1:
        return {3 * std::cos(3 * s), std::exp(s), 5 * std::pow(s, 4) - 2 * s};
      case 2:
        return {-9 * std::sin(3 * s), std::exp(s), 20 * std::pow(s, 3) - 2};
      default:
        return {-27 * std::cos(3 * s), std::exp(s), 60 * s * s};
    }
  };
  const double tolerance[4] = {0, 1e-11, 1e-10, 1e-9};
  double worst[4] = {0, 0, 0, 0};
  for (int r = 1; r <= 3; ++r)
    for (double s : {0.0, 0.1, 0.5, 0.9, 1.0}) {
      const NumericalDerivative d = numerical_derivative(f, r, s);
      const double err =
          (d.value - exact(r, s)).cwiseAbs().maxCoeff() / std::max(1.0, exact(r, s).cwiseAbs().maxCoeff());
      worst[r] = std::max(worst[r], err);
      CHECK_FALSE(d.one_sided);
    }
  INFO("relative errors: order 1 " << worst[1] << ", order 2 " << worst[2] << ", order 3 " << worst[3]);
  for (int r = 1; r <= 3; ++r) CHECK(worst[r] < tolerance[r]);
}

TEST_CASE("numerical_derivative: a first step too large for the function is not trusted", "[curves]") {
  // sin(ωs) for ω up to 50 (8 periods on [0, 1]): the first tableau, from h = 0.1, is wrong for the
  // fast ones; the smaller starts agree and win.
  for (double w : {1.0, 2 * M_PI, 6 * M_PI, 50.0})
    for (int r = 1; r <= 3; ++r)
      for (double s : {0.0, 0.3, 0.55, 1.0}) {
        auto f = [w](double x) { return Eigen::RowVector3d(std::sin(w * x), std::cos(w * x), 0); };
        const double scale = std::pow(w, r);
        const Eigen::RowVector3d exact(scale * std::sin(w * s + r * M_PI / 2), scale * std::cos(w * s + r * M_PI / 2),
                                       0);
        const NumericalDerivative d = numerical_derivative(f, r, s);
        INFO("w = " << w << ", order " << r << ", s = " << s);
        CHECK((d.value - exact).cwiseAbs().maxCoeff() / scale < (r == 3 ? 1e-9 : 1e-10));
      }
}

TEST_CASE("numerical_derivative: detail at 1e-3 of the parameter still has its derivatives", "[curves]") {
  // sin(1000 s)/1000: until 2026-11-30 the four starts (down to h = 0.1/64) never agreed, and a
  // ruled surface with this side had no normal, curvature or twist anywhere.
  // (At ω = 3000 the third derivative needs steps where rounding is larger than 1e-7 of it.)
  for (double w : {300.0, 1000.0, 3000.0})
    for (int r = 1; r <= (w > 1000 ? 2 : 3); ++r)
      for (double s : {0.0, 0.3, 0.55}) {
        auto f = [w](double x) { return Eigen::RowVector3d(x, 0, std::sin(w * x) / w); };
        const double scale = std::pow(w, r - 1);  // of the derivative of the third coordinate
        const double exact = scale * std::sin(w * s + r * M_PI / 2);
        const NumericalDerivative d = numerical_derivative(f, r, s);
        INFO("w = " << w << ", order " << r << ", s = " << s << ": " << d.value(2) << " against " << exact
                    << ", estimate " << d.error_estimate);
        CHECK(std::abs(d.value(2) - exact) / scale < (r == 3 ? 1e-7 : 1e-9));
        CHECK(std::abs(d.value(2) - exact) <= std::max(10 * d.error_estimate, 1e-12 * scale));
      }
}

TEST_CASE("numerical_derivative: one-sided near a domain end where the function stops", "[curves]") {
  // sqrt(s + 1e-3)·(1,1,1) is NaN for s < −1e-3: central differences at s = 0 are impossible.
  auto f = [](double s) { return Eigen::RowVector3d::Constant(std::sqrt(s + 1)); };
  auto g = [&](double s) { return s < 0 ? Eigen::RowVector3d::Constant(std::nan("")) : f(s); };
  const NumericalDerivative d = numerical_derivative(g, 1, 0);
  CHECK(d.one_sided);
  CHECK(std::abs(d.value(0) - 0.5) < 1e-7);
  // Inside, close to the end: central differences with a smaller first step.
  const NumericalDerivative e = numerical_derivative(g, 1, 0.05);
  CHECK_FALSE(e.one_sided);
  CHECK(std::abs(e.value(0) - 0.5 / std::sqrt(1.05)) < 1e-10);
}

TEST_CASE("numerical_derivative: a function that is another one outside the domain is differentiated inside it",
          "[curves]") {
  // |sin πs| is sin πs on [0, 1] and has kinks at its ends: central differences there read the
  // other branch (the derivative at 0 was 0, not π)
  auto f = [](double s) { return Eigen::RowVector3d(std::abs(std::sin(M_PI * s)), 0.1 * s, 0); };
  auto smooth = [](double s) { return Eigen::RowVector3d(std::sin(M_PI * s), 0.1 * s, 0); };
  for (const double s : {0.0, 0.02, 0.97, 1.0}) {
    INFO("s = " << s);
    const Eigen::RowVector3d exact1(M_PI * std::cos(M_PI * s), 0.1, 0), exact2(-M_PI * M_PI * std::sin(M_PI * s), 0, 0);
    CHECK((numerical_derivative(f, 1, s).value - exact1).cwiseAbs().maxCoeff() < 1e-6);
    CHECK((numerical_derivative(f, 2, s).value - exact2).cwiseAbs().maxCoeff() < 1e-3);
    // a function smooth across the end keeps the central estimate, to its accuracy
    CHECK((numerical_derivative(smooth, 1, s).value - exact1).cwiseAbs().maxCoeff() < 1e-12);
    CHECK_FALSE(numerical_derivative(smooth, 1, s).one_sided);
  }
}

TEST_CASE("AnalyticCurve: expressions in t on [t1, t2], reparametrised to [0, 1] (LN1)", "[curves]") {
  const AnalyticCurve c({"cos(t)", "sin(t)", "t^2 + 1e-3"}, 0.5, 2.0);
  for (double s : {0.0, 0.25, 1.0}) {
    const double t = 0.5 + 1.5 * s;
    CHECK((c.at(s) - Eigen::RowVector3d(std::cos(t), std::sin(t), t * t + 1e-3)).norm() < 1e-15);
    // d/ds = 1.5 d/dt, d²/ds² = 2.25 d²/dt².
    CHECK((c.derivative(1, s) - 1.5 * Eigen::RowVector3d(-std::sin(t), std::cos(t), 2 * t)).norm() < 1e-9);
    CHECK((c.derivative(2, s) - 2.25 * Eigen::RowVector3d(-std::cos(t), -std::sin(t), 2)).norm() < 1e-7);
  }
  // The parameter may be called u, v or s too; pi and e are constants.
  const AnalyticCurve d({"u", "sin(pi/2*v)", "e^s"});
  CHECK((d.at(0.5) - Eigen::RowVector3d(0.5, std::sin(M_PI / 4), std::exp(0.5))).norm() < 1e-15);
  // Copies are independent.
  // NOLINTNEXTLINE(performance-unnecessary-copy-initialization): the copy constructor is what is tested here
  const AnalyticCurve copy = c;
  CHECK(copy.at(0.3) == c.at(0.3));
}

TEST_CASE("AnalyticCurve: an expression that does not parse names its component", "[curves]") {
  try {
    AnalyticCurve c({"t", "2*t-", "0"});
    FAIL("no exception");
  } catch (const ExpressionError& e) {
    CHECK(e.component() == 1);
    CHECK(std::string(e.what()).find("2*t-") != std::string::npos);
  }
  CHECK_THROWS_AS(AnalyticCurve({"t", "0", "foo(t)"}), ExpressionError);
  CHECK_THROWS_AS(AnalyticCurve({"x", "0", "0"}), ExpressionError);     // unknown variable
  CHECK_THROWS_AS(AnalyticCurve({"t, 2", "0", "0"}), ExpressionError);  // two values
  CHECK_THROWS_AS(AnalyticCurve({"", "0", "0"}), ExpressionError);
}

TEST_CASE("AnalyticCurve: an assignment is refused, and no component reaches another's variable", "[curves]") {
  // "t=0.5" in y set the t that z then read: r(1) came out (1, 0.5, 0.5)
  for (const char* y : {"t=0.5", "t+=1", "(t = 2) * 0", "t *= 2"}) {
    INFO(y);
    try {
      AnalyticCurve c({"t", y, "t"});
      FAIL("no exception");
    } catch (const ExpressionError& e) {
      CHECK(e.component() == 1);
      CHECK_THAT(e.what(), Catch::Contains("assigns to a variable"));
    }
  }
  // comparisons are not assignments
  const AnalyticCurve c({"t", "t==1 ? 2 : (t<=0.5) + (t>=0.75) + (t!=0.25)", "t"});
  CHECK(c.at(1.0) == Eigen::RowVector3d(1, 2, 1));
  CHECK(c.at(0.25) == Eigen::RowVector3d(0.25, 1, 0.25));
  CHECK(c.at(0.8) == Eigen::RowVector3d(0.8, 2, 0.8));
}

TEST_CASE("AnalyticCurve: an infinite derivative is NaN, not a number", "[curves]") {
  const AnalyticCurve c({"t", "sqrt(t)", "0"});
  CHECK(std::isnan(c.derivative(1, 0)(1)));
  CHECK(std::abs(c.derivative(1, 0.25)(1) - 1.0) < 1e-9);
}

TEST_CASE("AnalyticCurve: a curve far from the origin keeps its derivatives, a singular one stays NaN", "[curves]") {
  // Rounding of values near 1e8 disagrees by about 1 % in a second derivative: it was read as "no
  // derivative", so the surface's curvatures came out 0 and join compared no normals.
  for (const auto& [offset, accuracy] : {std::pair{1e6, 1e-4}, std::pair{1e8, 2e-2}}) {
    const AnalyticCurve near({"cos(t)", "sin(t)", "t"}, 0.0, 2.0);
    const AnalyticCurve far({std::to_string(offset) + " + cos(t)", "sin(t)", "t"}, 0.0, 2.0);
    for (int r = 1; r <= 2; ++r)
      for (const double s : {0.0, 0.3, 1.0}) {
        INFO("offset " << offset << ", order " << r << ", s = " << s);
        const Eigen::RowVector3d exact = near.derivative(r, s), d = far.derivative(r, s);
        REQUIRE(d.allFinite());
        CHECK((d - exact).cwiseAbs().maxCoeff() <= accuracy * exact.cwiseAbs().maxCoeff());
      }
    const AnalyticCurve root({std::to_string(offset) + " + t", "sqrt(t)", "0"});
    CHECK(root.derivative(1, 0.0).hasNaN());
  }
}

TEST_CASE("fit_bezier: interpolates the ends, exact for polynomials, deviation falls with the degree", "[curves]") {
  // A polynomial of degree 3 written as expressions: fitted exactly at degree ≥ 3.
  const Curve cubic = AnalyticCurve({"t", "t^3 - t", "2*t^2"});
  const BezierFit exact = fit_bezier(cubic, 4);
  CHECK(exact.max_deviation < 1e-13);
  CHECK((exact.curve.points.row(0) - cubic.at(0)).norm() == 0);
  CHECK((exact.curve.points.row(4) - cubic.at(1)).norm() == 0);

  // LN0's quarter circle (u, sin(πu/2), cos(πu/2)): the error falls fast with the degree.
  const Curve arc = AnalyticCurve({"u", "sin(pi/2*u)", "cos(pi/2*u)"});
  double previous = 1;
  for (int degree : {2, 3, 4, 6, 8}) {
    const BezierFit fit = fit_bezier(arc, degree);
    INFO("degree " << degree << ": " << fit.max_deviation);
    CHECK(fit.max_deviation < previous);
    CHECK((fit.curve.points.row(0) - arc.at(0)).norm() == 0);
    CHECK((fit.curve.points.row(degree) - arc.at(1)).norm() == 0);
    // The reported deviation is the true maximum on a fine grid, to within the grid's resolution.
    double check = 0;
    for (int k = 0; k <= 997; ++k) check = std::max(check, (evaluate(fit.curve, k / 997.0) - arc.at(k / 997.0)).norm());
    CHECK(check <= fit.max_deviation * (1 + 1e-3) + 1e-15);
    previous = fit.max_deviation;
  }
  CHECK(previous < 1e-7);

  // A Bézier curve of lower degree is elevated, not fitted.
  const BezierFit elevated_fit = fit_bezier(Curve(make_random_bezier(2, 5)), 5);
  CHECK(elevated_fit.max_deviation == 0);
  CHECK(elevated_fit.curve.degree() == 5);
}

TEST_CASE("fit_bezier: above degree 24 a fit up to degree 64 at rounding level, else degree 24, and its degree said",
          "[curves]") {
  // Six periods of a sine: the degree-24 fit deviates by 1.6e-3; degree 56 is at rounding. Until
  // 2026-11-30 every degree above 24 returned the degree-24 fit, elevated.
  const Curve wave = AnalyticCurve({"t", "0", "0.1*sin(12*pi*t)"});
  const BezierFit at24 = fit_bezier(wave, 24);
  CHECK(at24.max_deviation > 1e-4);
  CHECK(at24.fitted_degree == 24);
  const BezierFit at30 = fit_bezier(wave, 30);  // nothing up to 30 at rounding: the fit at 24
  CHECK(at30.fitted_degree == 24);
  CHECK(at30.max_deviation == at24.max_deviation);
  CHECK(at30.curve.degree() == 30);
  // A curve no degree fits to rounding (|t − 0.3|^1.5): the fits above 24 were made of the
  // system's ill-conditioning, control points of 3e9 at degree 48 for a curve of size 0.6.
  const Curve kink = AnalyticCurve({"t", "0", "abs(t - 0.3)^1.5"});
  const BezierFit at48 = fit_bezier(kink, 48);
  CHECK(at48.fitted_degree == 24);
  CHECK(at48.curve.points.cwiseAbs().maxCoeff() < 2);
  const BezierFit at200 = fit_bezier(wave, 200);
  INFO("degree 200: " << at200.max_deviation << " (fitted at " << at200.fitted_degree << ")");
  CHECK(at200.curve.degree() == 200);
  CHECK(at200.fitted_degree > 24);
  CHECK(at200.fitted_degree <= kLargestFitDegree);
  CHECK(at200.max_deviation < 1e-13);
  // The reported deviation is the curve's, checked here on a grid of another step.
  double check = 0;
  for (int k = 0; k <= 4999; ++k)
    check = std::max(check, (evaluate(at200.curve, k / 4999.0) - wave.at(k / 4999.0)).norm());
  CHECK(check <= 2 * at200.max_deviation + 1e-15);
  // The elevation is exact: the control polygon of the elevated fit stays near the curve.
  CHECK((at200.curve.points.row(100) - wave.at(0.5)).norm() < 0.1);
}
