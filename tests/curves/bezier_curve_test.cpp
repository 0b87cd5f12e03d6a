#include "coons/curves/bezier_curve.h"

#include <array>
#include <catch2/catch.hpp>
#include <vector>

#include "coons/curves/curve.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// Σ_i P_i d^r B_i^k(t), with the textbook derivative of the basis (fixtures.h).
Eigen::RowVector3d reference_derivative(const BezierCurve& c, int r, double t) {
  const Eigen::VectorXd B = bernstein_basis_derivative(c.degree(), r, t);
  return B.transpose() * c.points;
}

const double kParameters[] = {0.0, 0.13, 0.5, 0.77, 1.0};

}  // namespace

TEST_CASE("evaluate (curve): de Casteljau agrees with the Bernstein sum at every degree", "[curves]") {
  for (int k = 0; k <= 12; ++k) {
    const BezierCurve c = make_random_bezier(k, 10 + k);
    for (double t : kParameters) CHECK((evaluate(c, t) - bezier_curve(c.points, t)).norm() < 1e-14);
  }
}

TEST_CASE("evaluate_derivative (curve): every order equals the textbook basis derivative", "[curves]") {
  for (int k = 1; k <= 9; ++k) {
    const BezierCurve c = make_random_bezier(k, 40 + k);
    for (int r = 1; r <= k + 1; ++r)
      for (double t : kParameters) {
        INFO("degree " << k << ", order " << r << ", t = " << t);
        const Eigen::RowVector3d expected = r > k ? Eigen::RowVector3d::Zero() : reference_derivative(c, r, t);
        CHECK((evaluate_derivative(c, r, t) - expected).norm() < 1e-10 * std::max(1.0, expected.norm()));
      }
  }
}

TEST_CASE("elevated: the curve does not change", "[curves]") {
  const BezierCurve c = make_random_bezier(4, 7);
  for (int d : {4, 5, 9}) {
    const BezierCurve e = elevated(c, d);
    REQUIRE(e.degree() == d);
    for (double t : kParameters) CHECK((evaluate(e, t) - evaluate(c, t)).norm() < 1e-14);
  }
  // A point elevates to a constant curve.
  const BezierCurve p = elevated(BezierCurve(Eigen::MatrixX3d(Eigen::RowVector3d(1, 2, 3))), 3);
  for (double t : kParameters) CHECK(evaluate(p, t) == Eigen::RowVector3d(1, 2, 3));
}

TEST_CASE("subdivide: the halves are the curve on [0, t] and [t, 1]", "[curves]") {
  for (int k : {1, 3, 7}) {
    const BezierCurve c = make_random_bezier(k, 90 + k);
    for (double t : {0.3, 0.5, 0.81}) {
      const auto [a, b] = subdivide(c, t);
      REQUIRE(a.degree() == k);
      REQUIRE(b.degree() == k);
      for (double s : kParameters) {
        CHECK((evaluate(a, s) - evaluate(c, s * t)).norm() < 1e-14);
        CHECK((evaluate(b, s) - evaluate(c, t + s * (1 - t))).norm() < 1e-14);
      }
      // They join at c(t) with tangents in the ratio of the lengths of the pieces.
      CHECK((a.points.row(k) - b.points.row(0)).norm() == 0);
      CHECK((evaluate_derivative(a, 1, 1) / t - evaluate_derivative(b, 1, 0) / (1 - t)).norm() < 1e-12);
    }
  }
}

TEST_CASE("reparametrised: LN1's t = t1 + s(t2 - t1), exactly, also reversed and outside [0, 1]", "[curves]") {
  const BezierCurve c = make_random_bezier(5, 3);
  for (auto [t1, t2] : {std::pair{0.2, 0.7}, {0.9, 0.1}, {-0.5, 1.5}, {0.0, 1.0}}) {
    const BezierCurve r = reparametrised(c, t1, t2);
    for (double s : kParameters) {
      const double t = t1 + s * (t2 - t1);
      CHECK((evaluate(r, s) - evaluate(c, t)).norm() < 1e-12);
      // Chain rule: d/ds = (t2 − t1) d/dt.
      CHECK((evaluate_derivative(r, 1, s) - (t2 - t1) * evaluate_derivative(c, 1, t)).norm() < 1e-11);
    }
  }
}

TEST_CASE("Curve::hermite_cubic: the Ferguson cubic has the given ends and end tangents", "[curves]") {
  const Eigen::RowVector3d p0(0, 0, 1), p1(1, 2, 0), d0(1, 0, -1), d1(0, 3, 2);
  const Curve c = Curve::hermite_cubic(p0, p1, d0, d1);
  CHECK((c.at(0) - p0).norm() < 1e-15);
  CHECK((c.at(1) - p1).norm() < 1e-15);
  CHECK((c.derivative(1, 0) - d0).norm() < 1e-14);
  CHECK((c.derivative(1, 1) - d1).norm() < 1e-14);
  for (double t : kParameters) {
    const Eigen::RowVector3d h = hermite(0, t) * p0 + hermite(1, t) * p1 + hermite(2, t) * d0 + hermite(3, t) * d1;
    CHECK((c.at(t) - h).norm() < 1e-14);
  }
}

namespace {

// de Casteljau in long double: the reference for the O(k) sum at high degree
Eigen::RowVector3d de_casteljau_long(const Eigen::MatrixX3d& P, double t) {
  std::vector<std::array<long double, 3>> q(size_t(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) q[size_t(i)] = {P(i, 0), P(i, 1), P(i, 2)};
  const long double s = t;
  for (size_t k = q.size() - 1; k >= 1; --k)
    for (size_t i = 0; i < k; ++i)
      for (int d = 0; d < 3; ++d) q[i][d] = (1 - s) * q[i][d] + s * q[i + 1][d];
  return {double(q[0][0]), double(q[0][1]), double(q[0][2])};
}

}  // namespace

TEST_CASE("bernstein_sum: agrees with de Casteljau in long double to 1e-13 up to degree 5000", "[curves]") {
  for (const int k : {1, 7, 101, 1000, 5000}) {
    const BezierCurve c = make_random_bezier(k, 11);
    const double size = c.points.cwiseAbs().maxCoeff();
    for (const double t : {0.0, 1e-300, 1e-9, 0.013, 0.25, 0.5, 0.61803, 0.999, 1.0 - 1e-12, 1.0}) {
      INFO("degree " << k << ", t = " << t);
      CHECK((bernstein_sum(c.points, t) - de_casteljau_long(c.points, t)).norm() <= 1e-13 * size);
      if (k > kDeCasteljauMaxDegree) CHECK(evaluate(c, t) == bernstein_sum(c.points, t));
    }
  }
}

TEST_CASE("bernstein_sum: reproduces constants and lines at any degree", "[curves]") {
  for (const int k : {150, 2000}) {
    Eigen::MatrixX3d P(k + 1, 3);
    for (int i = 0; i <= k; ++i) P.row(i) << 2.5, double(i) / k, 1 - 3.0 * i / k;
    for (const double t : {0.0, 0.1, 0.5, 0.77, 1.0}) {
      const Eigen::RowVector3d p = bernstein_sum(P, t);
      CHECK(p(0) == Approx(2.5).epsilon(1e-15));
      CHECK(p(1) == Approx(t).epsilon(0).margin(1e-14));
      CHECK(p(2) == Approx(1 - 3 * t).epsilon(0).margin(1e-14));
    }
  }
}
