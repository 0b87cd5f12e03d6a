// Every worked example of the lecture notes LN0–LN4 (docs/references.md) (data/surfaces/) against its closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "coons/io/surface_io.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/surfaces/conoid.h"
#include "coons/surfaces/surface.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using V = Eigen::RowVector3d;

namespace {

std::string fmt_number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

Surface load(const std::string& name) { return read_surface_file(surface_data(name)).surface; }

// max over a grid of the distance between the surface and a closed form.
double gap(const Surface& s, const std::function<V(double, double)>& closed, int n = 11) {
  return max_distance([&](double u, double v) { return s.at(u, v); }, closed, n);
}

// The same for a partial derivative ∂^a_u ∂^b_v.
double derivative_gap(const Surface& s, int a, int b, const std::function<V(double, double)>& closed, int n = 9) {
  return max_distance([&](double u, double v) { return s.evaluate(u, v).derivative(a, b); }, closed, n);
}

}  // namespace

TEST_CASE("LN0, bilinear Coons example 1: the patch is (u+v, u^2-v^2, 1-u+v)", "[surfaces][seeds]") {
  const Surface s = load("seed000_bilinear_coons_1.json");
  CHECK(s.type() == SurfaceType::kBilinearCoons);
  CHECK(gap(s, [](double u, double v) { return V(u + v, u * u - v * v, 1 - u + v); }) < 1e-14);
  // Derivatives through the numerically differentiated expressions.
  CHECK(derivative_gap(s, 1, 0, [](double u, double) { return V(1, 2 * u, -1); }) < 1e-8);
  CHECK(derivative_gap(s, 0, 1, [](double, double v) { return V(1, -2 * v, 1); }) < 1e-8);
  CHECK(derivative_gap(s, 2, 0, [](double, double) { return V(0, 2, 0); }) < 1e-6);
  CHECK(derivative_gap(s, 0, 2, [](double, double) { return V(0, -2, 0); }) < 1e-6);
  CHECK(derivative_gap(s, 1, 1, [](double, double) { return V(0, 0, 0); }) < 1e-6);
  // As a net: the expressions are quadratics, found as such (fits of degree 2 reproduce them to
  // rounding, so no higher degree is used), and the degree (2, 2) net's interior point is
  // (1, 0, 1) (docs/math.md §7.1), the discrete Coons net of its boundary.
  const FittedNet net = fitted_net(s, 6);
  CHECK_FALSE(net.exact);
  for (const auto& f : net.fits) CHECK(f.degree == 2);
  REQUIRE(net.net.m == 2);
  REQUIRE(net.net.n == 2);
  CHECK(net.max_curve_deviation < 1e-14);
  CHECK((net.net.at(1, 1) - V(1, 0, 1)).norm() < 1e-14);
  CHECK((net.net.points - discrete_coons_net(boundary_of(net.net)).points).cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("LN0, bilinear Coons example 2 and the hyperbolic paraboloid: z = 2uv", "[surfaces][seeds]") {
  auto paraboloid = [](double u, double v) { return V(u, v, 2 * u * v); };
  const Surface coons = load("seed000_bilinear_coons_2.json");
  CHECK(gap(coons, paraboloid) < 1e-15);
  CHECK(derivative_gap(coons, 1, 1, [](double, double) { return V(0, 0, 2); }) < 1e-7);
  const Surface bilinear = load("seed000_hyperbolic_paraboloid.json");
  CHECK(bilinear.type() == SurfaceType::kBilinear);
  CHECK(gap(bilinear, paraboloid) < 1e-15);
  CHECK(derivative_gap(bilinear, 1, 1, [](double, double) { return V(0, 0, 2); }) < 1e-15);
  const ControlNet net = *bilinear.bezier_net();
  CHECK(net.m == 1);
  CHECK(net.n == 1);
  CHECK((net.at(1, 1) - V(1, 1, 2)).norm() == 0);
}

TEST_CASE("LN0, partially bicubic Coons example 1: (u, v, 2u F1(v) + 2v F1(u) - 2 F1(u) F1(v))", "[surfaces][seeds]") {
  const Surface s = load("seed000_hermite_coons_1.json");
  CHECK(s.type() == SurfaceType::kHermiteCoons);
  auto F1 = [](double t) { return 3 * t * t - 2 * t * t * t; };
  CHECK(gap(s, [&](double u, double v) { return V(u, v, 2 * u * F1(v) + 2 * v * F1(u) - 2 * F1(u) * F1(v)); }) < 1e-14);
  // Not the hyperbolic paraboloid of the bilinear blend: the blends matter.
  CHECK(gap(s, [](double u, double v) { return V(u, v, 2 * u * v); }) > 0.01);
}

TEST_CASE("LN0, the Ferguson examples: (u, v, H03(v) - H03(u) H13(v)) and the flat square", "[surfaces][seeds]") {
  const Surface s = load("seed000_ferguson_1.json");
  CHECK(gap(s, [](double u, double v) { return V(u, v, hermite(0, v) - hermite(0, u) * hermite(2, v)); }) < 1e-15);
  const Surface square = load("seed000_ferguson_square.json");
  CHECK(gap(square, [](double u, double v) { return V(u, v, 0); }) < 1e-15);
}

TEST_CASE("LN0, the 16-vector example: z = T H13(u) H13(v) for several T", "[surfaces][seeds]") {
  const std::array<V, 4> corners = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)};
  const std::array<V, 4> du = {V(1, 0, 0), V(1, 0, 0), V(1, 0, 0), V(1, 0, 0)};
  const std::array<V, 4> dv = {V(0, 1, 0), V(0, 1, 0), V(0, 1, 0), V(0, 1, 0)};
  for (double T : {-3.0, 0.0, 1.0, 10.0, 20.0, 100.0}) {
    INFO("T = " << T);
    const Surface s = make_hermite16(HermitePatch{corners, du, dv, {V(0, 0, T), V(0, 0, 0), V(0, 0, 0), V(0, 0, 0)}});
    auto closed = [T](double u, double v) { return V(u, v, T * hermite(2, u) * hermite(2, v)); };
    CHECK(gap(s, closed) < 1e-13 * std::max(1.0, T));
    CHECK(derivative_gap(s, 1, 1, [T](double u, double v) {
            return V(0, 0, T * hermite(2, u, 1) * hermite(2, v, 1));
          }) < 1e-13 * std::max(1.0, T));
    // Bézier form at the (0,0) corner: b11 = p + r_u/3 + r_v/3 + r_uv/9 (docs/math.md §6).
    const ControlNet net = *s.bezier_net();
    CHECK((net.at(1, 1) - V(1.0 / 3, 1.0 / 3, T / 9)).norm() < 1e-15 * std::max(1.0, T));
    for (int i = 0; i <= 3; ++i)
      for (int j = 0; j <= 3; ++j)
        if (i != 1 || j != 1) CHECK(std::abs(net.at(i, j)(2)) < 1e-15 * std::max(1.0, T));
  }
  for (double T : {10.0, 20.0}) {
    const Surface s = load(T == 10 ? "seed000_hermite16_T10.json" : "seed000_hermite16_T20.json");
    CHECK(gap(s, [T](double u, double v) { return V(u, v, T * hermite(2, u) * hermite(2, v)); }) < 1e-13 * T);
  }
}

TEST_CASE("LN0, ruled examples: r = (1-v) r(u,0) + v r(u,1) with the seed's curves", "[surfaces][seeds]") {
  const Surface s1 = load("seed000_ruled_1.json");
  auto c0 = [](double u) { return V(u, std::sin(M_PI / 2 * u), std::cos(M_PI / 2 * u)); };
  auto c1 = [](double u) { return V(u, u * u, -u / 2); };
  CHECK(gap(s1, [&](double u, double v) { return V((1 - v) * c0(u) + v * c1(u)); }) < 1e-15);
  CHECK(derivative_gap(s1, 1, 0, [&](double u, double v) {
          return V((1 - v) * V(1, M_PI / 2 * std::cos(M_PI / 2 * u), -M_PI / 2 * std::sin(M_PI / 2 * u)) +
                   v * V(1, 2 * u, -0.5));
        }) < 1e-9);
  CHECK(derivative_gap(s1, 0, 1, [&](double u, double) { return V(c1(u) - c0(u)); }) < 1e-15);
  CHECK(derivative_gap(s1, 0, 2, [](double, double) { return V(0, 0, 0); }) == 0);

  const Surface s2 = load("seed000_ruled_2.json");
  CHECK(gap(s2, [](double u, double v) {
          return V((1 - v) * V(u, 0, 4 * u * (1 - u)) + v * V(u, 1, std::sin(2 * M_PI * u)));
        }) < 1e-15);
}

TEST_CASE("LN0, the right parabolic conoid: the file and make_conoid give x = u, y = y_P(1-v), z = z_P + v(z(u) - z_P)",
          "[surfaces][seeds]") {
  // The data file: z(u) = 4u(1 - u) as a quadratic Bézier, y_P = 1, z_P = 0.5: an exact net of degree (2, 1).
  const Surface s = load("seed000_parabolic_conoid.json");
  auto closed = [](double yp, double zp, double u, double v) {
    return V(u, yp * (1 - v), zp + v * (4 * u * (1 - u) - zp));
  };
  CHECK(gap(s, [&](double u, double v) { return closed(1, 0.5, u, v); }) < 1e-15);
  const ControlNet net = *s.bezier_net();
  CHECK(net.m == 2);
  CHECK(net.n == 1);
  // The same with an analytic parabola and other lines, through LN0's right-conoid form.
  for (auto [yp_bound, zp_bound] : {std::pair{2.0, 0.0}, {-1.0, 3.0}, {0.5, 1.0}}) {
    const double yp = yp_bound, zp = zp_bound;  // C++17 lambdas cannot capture structured bindings
    const Surface e = make_conoid(right_conoid(AnalyticCurve({"t", "0", "4*t*(1-t)"}), yp, zp));
    CHECK(gap(e, [&](double u, double v) { return closed(yp, zp, u, v); }) < 1e-14);
    CHECK(derivative_gap(e, 1, 1, [](double u, double) { return V(0, 0, 4 - 8 * u); }) < 1e-8);
  }
}

TEST_CASE("LN0, right circular and elliptic conoids, and an oblique (Kuepper-type) circular conoid: their closed forms",
          "[surfaces][seeds]") {
  // Right conoids over a half ellipse (a cos θ, 0, b sin θ), θ = π(1 − u): x = x(u), y = y_P(1 − v),
  // z = z_P + v(z(u) − z_P); a = b is the circular conoid.
  for (auto [a_bound, b_bound] : {std::pair{1.0, 1.0}, {2.0, 0.7}}) {
    const double a = a_bound, b = b_bound;  // C++17 lambdas cannot capture structured bindings
    const Curve profile = AnalyticCurve({fmt_number(a) + "*cos(t)", "0", fmt_number(b) + "*sin(t)"}, M_PI, 0);
    const double yp = 3, zp = 0.25;
    const Surface s = make_conoid(right_conoid(profile, yp, zp));
    auto closed = [&](double u, double v) {
      const double th = M_PI * (1 - u);
      return V(a * std::cos(th), yp * (1 - v), zp + v * (b * std::sin(th) - zp));
    };
    CHECK(gap(s, closed) < 1e-14);
    CHECK(derivative_gap(s, 1, 0, [&](double u, double v) {
            const double th = M_PI * (1 - u);
            return V(M_PI * a * std::sin(th), 0, -v * M_PI * b * std::cos(th));
          }) < 1e-9);
    // The rulings are parallel to the directing plane x = const.
    for (double u : {0.2, 0.7}) CHECK(std::abs(s.evaluate(u, 0.4).dv(0)) < 1e-15);
  }
  // Oblique: the line through the origin along (1, 0, 1) is not perpendicular to the planes x = const.
  // Directrix the circle (cos θ, 1, sin θ): q = (cos θ, 0, cos θ), r = (cos θ, v, (1 − v) cos θ + v sin θ).
  Conoid oblique{AnalyticCurve({"cos(t)", "1", "sin(t)"}, 0, M_PI), V(0, 0, 0), V(1, 0, 1), V(1, 0, 0)};
  const Surface o = make_conoid(oblique);
  CHECK(gap(o, [](double u, double v) {
          const double th = M_PI * u;
          return V(std::cos(th), v, (1 - v) * std::cos(th) + v * std::sin(th));
        }) < 1e-15);
  // A Bézier directrix makes it polynomial: an exact net of degree (deg c, 1).
  Conoid oblique_poly = oblique;
  oblique_poly.directrix = make_random_bezier(4, 9);
  const ControlNet net = *make_conoid(oblique_poly).bezier_net();
  CHECK(net.m == 4);
  CHECK(net.n == 1);
}

TEST_CASE("LN2, the right helicoidal conoid: (u cos v, u sin v, v), its derivatives and curvatures",
          "[surfaces][seeds]") {
  // r(s, w) = P(w, 2πs): the directrix is parameterised by s, the rulings by w.
  auto P = [](double u, double v) { return V(u * std::cos(v), u * std::sin(v), v); };
  const Surface s = load("seed002_helicoidal_conoid.json");
  CHECK(gap(s, [&](double a, double w) { return P(w, 2 * M_PI * a); }) < 1e-14);
  // In code, with exact derivatives: r_s = (−2πw sin θ, 2πw cos θ, 2π), r_w = (cos θ, sin θ, 0).
  const Surface h = make_conoid(right_helicoidal_conoid(1, 0, 2 * M_PI));
  CHECK(gap(h, [&](double a, double w) { return P(w, 2 * M_PI * a); }) < 1e-14);
  CHECK(derivative_gap(h, 1, 0, [](double a, double w) {
          const double th = 2 * M_PI * a;
          return V(-2 * M_PI * w * std::sin(th), 2 * M_PI * w * std::cos(th), 2 * M_PI);
        }) < 1e-13);
  CHECK(derivative_gap(h, 0, 1, [](double a, double) { return V(std::cos(2 * M_PI * a), std::sin(2 * M_PI * a), 0); }) <
        1e-14);
  // A minimal surface: H = 0; K = −1/(1 + w²)² in the (w, θ) metric.
  for (double a : {0.1, 0.6})
    for (double w : {0.2, 0.9}) {
      const Curvatures c = curvatures(h.evaluate(a, w));
      CHECK(std::abs(c.mean) < 1e-12);
      CHECK(c.gaussian == Approx(-1 / std::pow(1 + w * w, 2)).epsilon(1e-12));
    }
}

TEST_CASE("LN2, the right circular conoid: (v, u, u sqrt(2v - v^2))", "[surfaces][seeds]") {
  const Surface s = load("seed002_circular_conoid.json");
  CHECK(gap(s, [](double a, double w) {
          const double x = 2 * a;
          return V(x, w, w * std::sqrt(std::max(0.0, 2 * x - x * x)));
        }) < 1e-14);
}

TEST_CASE("LN4, the linear Coons surface of the domain bounded by ellipse arcs: its closed form and derivative",
          "[surfaces][seeds]") {
  // r(u,v) = a(cos u + cos v − 1 + 2u(1 − cos v − sin v)/π + 2v(1 − cos u − sin u)/π) e1
  //        + b(sin u − sin v − 2u(1 − cos v − sin v)/π + 2v(1 − cos u − sin u)/π) e2,  u, v ∈ [0, π/2].
  auto closed = [](double a, double b, double u, double v) {
    const double p = 2 * u / M_PI * (1 - std::cos(v) - std::sin(v)), q = 2 * v / M_PI * (1 - std::cos(u) - std::sin(u));
    return V(a * (std::cos(u) + std::cos(v) - 1 + p + q), b * (std::sin(u) - std::sin(v) - p + q), 0);
  };
  auto closed_du = [](double a, double b, double u, double v) {  // ∂/∂u, u the seed's parameter
    const double p = 2 / M_PI * (1 - std::cos(v) - std::sin(v)), q = 2 * v / M_PI * (std::sin(u) - std::cos(u));
    return V(a * (-std::sin(u) + p + q), b * (std::cos(u) - p + q), 0);
  };
  const double h = M_PI / 2;  // s ∈ [0, 1] ↦ u = s·π/2
  const Surface s = load("seed004_ellipse_coons.json");
  CHECK(gap(s, [&](double x, double y) { return closed(2, 1, h * x, h * y); }) < 1e-14);
  CHECK(derivative_gap(s, 1, 0, [&](double x, double y) { return V(h * closed_du(2, 1, h * x, h * y)); }) < 1e-8);
  // Other ellipses, with exact curve derivatives.
  for (auto [a_bound, b_bound] : {std::pair{1.0, 1.0}, {3.0, 0.5}}) {
    const double a = a_bound, b = b_bound;  // C++17 lambdas cannot capture structured bindings
    auto arc = [h](const std::function<V(double)>& f, const std::function<V(double)>& df,
                   const std::function<V(double)>& d2f) {
      return closed_form_curve([=](double s) { return f(h * s); }, [=](double s) { return V(h * df(h * s)); },
                               [=](double s) { return V(h * h * d2f(h * s)); });
    };
    const Curve bottom = arc([=](double t) { return V(a * std::cos(t), b * std::sin(t), 0); },
                             [=](double t) { return V(-a * std::sin(t), b * std::cos(t), 0); },
                             [=](double t) { return V(-a * std::cos(t), -b * std::sin(t), 0); });
    const Curve top = arc([=](double t) { return V(-a * std::sin(t), -b * std::cos(t), 0); },
                          [=](double t) { return V(-a * std::cos(t), b * std::sin(t), 0); },
                          [=](double t) { return V(a * std::sin(t), b * std::cos(t), 0); });
    const Curve left = arc([=](double t) { return V(a * std::cos(t), -b * std::sin(t), 0); },
                           [=](double t) { return V(-a * std::sin(t), -b * std::cos(t), 0); },
                           [=](double t) { return V(-a * std::cos(t), b * std::sin(t), 0); });
    const Curve right = arc([=](double t) { return V(-a * std::sin(t), b * std::cos(t), 0); },
                            [=](double t) { return V(-a * std::cos(t), -b * std::sin(t), 0); },
                            [=](double t) { return V(a * std::sin(t), -b * std::cos(t), 0); });
    const Surface e = make_coons(BoundaryCurves{bottom, top, left, right}, CoonsBlending::kLinear);
    CHECK(gap(e, [&](double x, double y) { return closed(a, b, h * x, h * y); }) < 1e-14);
    CHECK(derivative_gap(e, 1, 0, [&](double x, double y) { return V(h * closed_du(a, b, h * x, h * y)); }) < 1e-14);
  }
}

TEST_CASE("LN4, the sectorial surface: (1-v) rho(u) + v p", "[surfaces][seeds]") {
  const Surface s = load("seed004_sectorial_cone.json");
  CHECK(s.type() == SurfaceType::kSectorial);
  CHECK(gap(s, [](double u, double v) {
          const double t = M_PI / 2 * u;
          return V((1 - v) * V(std::cos(t), std::sin(t), 0) + v * V(0, 0, 1));
        }) < 1e-15);
  // The apex row is a single point.
  CHECK((s.at(0.3, 1) - V(0, 0, 1)).norm() == 0);
}

TEST_CASE("data/surfaces: every file parses and has its line in data/README.md", "[surfaces][seeds]") {
  std::ifstream in(std::string(COONS_DATA_DIR) + "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(COONS_DATA_DIR) + "/surfaces")) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    INFO(name);
    CHECK_NOTHROW(read_surface_file(entry.path().string()));
    CHECK(readme.str().find("surfaces/" + name) != std::string::npos);
  }
  CHECK(files >= 15);
}
