#include "coons/net/bernstein.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "coons/surfaces/surface.h"

using namespace coons;

namespace {

// The de Casteljau triangle in long double: the reference for the O(k) values at high degree.
std::vector<long double> basis_long(int k, double t) {
  std::vector<long double> b(size_t(k) + 1, 0.0L);
  b[0] = 1;
  const long double u = t, s = 1 - u;
  for (int d = 1; d <= k; ++d) {
    for (int i = d; i >= 1; --i) b[size_t(i)] = s * b[size_t(i)] + u * b[size_t(i - 1)];
    b[0] *= s;
  }
  return b;
}

}  // namespace

TEST_CASE("bernstein_basis: agrees with de Casteljau in long double to 1e-13 of the largest value up to degree 5000",
          "[net]") {
  for (const int k : {1, 7, kDeCasteljauMaxDegree, kDeCasteljauMaxDegree + 1, 1000, 5000}) {
    for (const double t : {0.0, 1e-300, 1e-9, 0.013, 0.25, 0.5, 0.61803, 0.999, 1.0 - 1e-12, 1.0}) {
      INFO("degree " << k << ", t = " << t);
      const Eigen::VectorXd b = bernstein_basis(k, t);
      const std::vector<long double> reference = basis_long(k, t);
      REQUIRE(b.size() == k + 1);
      double worst = 0, largest = 0;
      for (int i = 0; i <= k; ++i) {
        worst = std::max(worst, std::abs(double(b(i) - reference[size_t(i)])));
        largest = std::max(largest, double(reference[size_t(i)]));
      }
      CHECK(worst <= 1e-13 * largest);
      CHECK(b.minCoeff() >= 0);
      CHECK(b.sum() == Approx(1).epsilon(1e-14));
    }
  }
}

TEST_CASE("bernstein_basis: is exact at the ends and one-sided when t is 0 or 1 at any degree", "[net]") {
  for (const int k : {3, 250, 4000}) {
    const Eigen::VectorXd at0 = bernstein_basis(k, 0.0), at1 = bernstein_basis(k, 1.0);
    CHECK(at0(0) == 1);
    CHECK(at0.tail(k).cwiseAbs().maxCoeff() == 0);
    CHECK(at1(k) == 1);
    CHECK(at1.head(k).cwiseAbs().maxCoeff() == 0);
  }
}

TEST_CASE("evaluate: a Bezier surface of degree 5000 by 1 reproduces its ruled-line parametrisation", "[net]") {
  // p(u, v) = (u, v, u²·v) is of degree 2 by 1; elevated to degree 5000 in u its control points are
  // (i/k, j, j·i(i−1)/(k(k−1))). The surface and its derivatives take the O(k) basis.
  const int k = 5000;
  ControlNet net(k, 1);
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= 1; ++j) net.at(i, j) << double(i) / k, j, j * double(i) * (i - 1) / (double(k) * (k - 1));
  const Surface s = make_bezier_surface(net);
  for (const double u : {0.0, 0.3, 0.75, 1.0})
    for (const double v : {0.0, 0.4, 1.0}) {
      INFO("u = " << u << ", v = " << v);
      const SurfacePoint p = s.evaluate(u, v);
      CHECK((p.p - Eigen::RowVector3d(u, v, u * u * v)).norm() <= 1e-13);
      CHECK((p.du - Eigen::RowVector3d(1, 0, 2 * u * v)).norm() <= 1e-11);
      CHECK((p.duu - Eigen::RowVector3d(0, 0, 2 * v)).norm() <= 1e-8);
      CHECK((p.duv - Eigen::RowVector3d(0, 0, 2 * u)).norm() <= 1e-11);
    }
}
