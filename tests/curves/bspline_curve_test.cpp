#include "coons/curves/bspline_curve.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/curves/bezier_curve.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// 201 parameters across the domain of c, ends included.
std::vector<double> parameters(const BSplineCurve& c, int k = 200) {
  std::vector<double> t;
  for (int i = 0; i <= k; ++i) t.push_back(c.start() + (c.end() - c.start()) * double(i) / k);
  return t;
}

double max_distance(const BSplineCurve& a, const BSplineCurve& b) {
  double worst = 0;
  for (double t : parameters(a)) worst = std::max(worst, (evaluate(a, t) - evaluate(b, t)).norm());
  return worst;
}

bool names_index(const std::vector<KnotProblem>& problems, int index) {
  for (const KnotProblem& p : problems)
    if (p.index == index && p.reason.find("knot " + std::to_string(index)) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("knot_vector_problems: random clamped vectors have none", "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p)
    for (int count = p + 1; count <= p + 12; ++count) {
      INFO("degree " << p << ", " << count << " points");
      CHECK(knot_vector_problems(make_random_knots(p, count, 100U * p + count), p, count).empty());
    }
  CHECK(knot_vector_problems(bezier_knots(3), 3, 4).empty());
}

TEST_CASE("knot_vector_problems: each violation is a reason naming the knot", "[curves][bspline]") {
  // Degree 3, 6 points: 10 knots.
  const Eigen::VectorXd valid = (Eigen::VectorXd(10) << 0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1).finished();
  REQUIRE(knot_vector_problems(valid, 3, 6).empty());
  SECTION("wrong length") {
    const Eigen::VectorXd one_short = valid.head(9);
    const auto problems = knot_vector_problems(one_short, 3, 6);
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].index == -1);
    CHECK(problems[0].reason.find("10 needed") != std::string::npos);
  }
  SECTION("decreasing") {
    Eigen::VectorXd U = valid;
    U(5) = 0.2;
    CHECK(names_index(knot_vector_problems(U, 3, 6), 5));
  }
  SECTION("not clamped at the start") {
    Eigen::VectorXd U = valid;
    U(3) = 0.1;
    CHECK(names_index(knot_vector_problems(U, 3, 6), 3));
  }
  SECTION("not clamped at the end") {
    Eigen::VectorXd U = valid;
    U(7) = 0.9;
    CHECK(names_index(knot_vector_problems(U, 3, 6), 7));
  }
  SECTION("not clamped at the end by one ulp: the two knots print differently") {
    Eigen::VectorXd U = valid;
    U(6) = std::nextafter(1.0, 0.0);  // "{:g}" printed both as 1: "knot 6 (1) differs from knot 9 (1)"
    const auto problems = knot_vector_problems(U, 3, 6);
    REQUIRE(names_index(problems, 6));
    CHECK(problems[0].reason.find("knot 6 (0.9999999999999999) differs from knot 9 (1)") != std::string::npos);
  }
  SECTION("first knot repeated too often") {
    Eigen::VectorXd U = valid;
    U(4) = 0;
    CHECK(names_index(knot_vector_problems(U, 3, 6), 4));
  }
  SECTION("interior multiplicity above the degree") {
    const Eigen::VectorXd U = (Eigen::VectorXd(12) << 0, 0, 0, 0, 0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1).finished();
    const auto problems = knot_vector_problems(U, 3, 8);
    REQUIRE(problems.size() == 1);
    CHECK(names_index(problems, 7));
  }
  SECTION("not finite") {
    Eigen::VectorXd U = valid;
    U(4) = std::nan("");
    CHECK(names_index(knot_vector_problems(U, 3, 6), 4));
  }
  SECTION("a span shorter than kMinKnotSpan of the range") {
    for (const double scale : {1.0, 1e-6, 1e12}) {
      INFO("knot range " << scale);
      Eigen::VectorXd U = scale * valid;
      U(4) = 1e-15 * scale;  // 1e-15 of the range after knot 3
      CHECK(names_index(knot_vector_problems(U, 3, 6), 4));
      U(4) = 0.3 * scale;
      U(5) = U(4) + 0.5 * kMinKnotSpan * scale;  // the span before knot 5
      CHECK(names_index(knot_vector_problems(U, 3, 6), 5));
      U(5) = U(4) + 2 * kMinKnotSpan * scale;  // twice the shortest span accepted
      CHECK(knot_vector_problems(U, 3, 6).empty());
    }
    // The denormal span of a helper's file: [0,0,0,1e-320,1,1,1] was read and gave null energies.
    const Eigen::VectorXd tiny = (Eigen::VectorXd(7) << 0, 0, 0, 1e-320, 1, 1, 1).finished();
    CHECK(names_index(knot_vector_problems(tiny, 2, 4), 3));
    // Its mirror: 0.9999999999999999 made two Greville abscissae coincide.
    const Eigen::VectorXd ulp = (Eigen::VectorXd(7) << 0, 0, 0, 0.9999999999999999, 1, 1, 1).finished();
    CHECK(names_index(knot_vector_problems(ulp, 2, 4), 4));
  }
  SECTION("degree 0 and too few points") {
    CHECK(knot_vector_problems(valid, 0, 9).size() == 1);
    CHECK_FALSE(knot_vector_problems(bezier_knots(3), 3, 3).empty());
  }
}

TEST_CASE("evaluate (B-spline): equals the Bernstein form on a Bézier knot vector", "[curves][bspline]") {
  for (int p = 1; p <= 9; ++p) {
    const BSplineCurve c = make_random_bspline(p, p + 1, 500U + p, -2.0, 3.0);
    REQUIRE(c.knots == bezier_knots(p, -2.0, 3.0));
    for (double t : parameters(c, 50)) {
      INFO("degree " << p << ", t = " << t);
      CHECK((evaluate(c, t) - bezier_curve(c.points, (t + 2.0) / 5.0)).norm() < 1e-14);
    }
  }
}

TEST_CASE("basis_functions: partition of unity, non-negative, local support", "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p)
    for (int count : {p + 1, p + 4, p + 11}) {
      const Eigen::VectorXd U = make_random_knots(p, count, 900U + 10U * p + count, -1.0, 4.0);
      for (int k = 0; k <= 300; ++k) {
        const double t = -1.0 + 5.0 * k / 300.0;
        const Eigen::VectorXd N = basis_functions(U, p, count, t);
        INFO("degree " << p << ", t = " << t);
        CHECK(std::abs(N.sum() - 1.0) < 1e-14);
        CHECK(N.minCoeff() >= -1e-15);
        CHECK((N.array() > 0).count() <= p + 1);
        const int span = find_span(U, p, t);
        CHECK(U(span) <= t);
        CHECK((t < U(span + 1) || span == count - 1));
        const Eigen::MatrixXd D = basis_derivatives(U, p, span, t, p);
        for (int r = 1; r <= p; ++r) CHECK(std::abs(D.row(r).sum()) < 1e-9 * (1.0 + D.row(r).cwiseAbs().sum()));
      }
    }
}

TEST_CASE("evaluate (B-spline): de Boor equals the sum of the basis functions", "[curves][bspline]") {
  for (int p = 1; p <= 6; ++p) {
    const BSplineCurve c = make_random_bspline(p, p + 7, 1300U + p);
    for (double t : parameters(c)) {
      const Eigen::RowVector3d sum = basis_functions(c.knots, p, c.count(), t).transpose() * c.points;
      CHECK((evaluate(c, t) - sum).norm() < 1e-14);
    }
  }
}

TEST_CASE("evaluate_derivative (B-spline): derivatives match finite differences and A2.3", "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p) {
    const BSplineCurve c = make_random_bspline(p, p + 6, 1700U + p, 0.0, 2.0);
    const auto distinct = knot_multiplicities(c.knots);
    for (int k = 0; k < 97; ++k) {
      const double t = 2.0 * (k + 0.5) / 97.0;
      // Central differences only where no knot lies within h (the pieces are polynomials there).
      const double h = 1e-5;
      bool near_knot = false;
      for (const auto& [u, s] : distinct) near_knot = near_knot || std::abs(u - t) < 2 * h;
      const int span = find_span(c.knots, p, t);
      const Eigen::MatrixXd D = basis_derivatives(c.knots, p, span, t, p + 1);
      for (int r = 1; r <= p + 1; ++r) {
        INFO("degree " << p << ", order " << r << ", t = " << t);
        const Eigen::RowVector3d d = evaluate_derivative(c, r, t);
        Eigen::RowVector3d from_basis = Eigen::RowVector3d::Zero();
        for (int j = 0; j <= p; ++j) from_basis += D(r, j) * c.points.row(span - p + j);
        CHECK((d - from_basis).norm() < 1e-9 * (1.0 + d.norm()));
        if (near_knot) continue;
        const Eigen::RowVector3d fd =
            (evaluate_derivative(c, r - 1, t + h) - evaluate_derivative(c, r - 1, t - h)) / (2 * h);
        CHECK((d - fd).norm() < 1e-5 * (1.0 + d.norm()));
      }
    }
  }
}

TEST_CASE("inserted_knot: leaves the curve unchanged and keeps multiplicities at most the degree",
          "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p) {
    const BSplineCurve c = make_random_bspline(p, p + 5, 2100U + p, -1.0, 1.0);
    BSplineCurve d = c;
    // New knots, existing knots and one knot inserted up to (and beyond) the degree.
    const std::vector<double> add = {-0.73, 0.05, c.knots(p + 1), c.knots(p + 2), 0.41, 0.41, 0.41, 0.41, 0.41, 0.9};
    d = refined(d, add);
    INFO("degree " << p);
    CHECK(knot_vector_problems(d.knots, d.degree, d.count()).empty());
    CHECK(d.count() > c.count());
    CHECK(max_distance(c, d) < 1e-13);
    CHECK(inserted_knot(c, c.end(), 1).count() == c.count());  // an end knot is not inserted
  }
}

TEST_CASE("degree_elevated: leaves the curve unchanged, every knot gains one multiplicity per step",
          "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p)
    for (int raise = 1; raise <= 3; ++raise) {
      const BSplineCurve c = make_random_bspline(p, p + 8, 2500U + 10U * p + raise, 0.5, 2.5);
      const BSplineCurve e = degree_elevated(c, p + raise);
      INFO("degree " << p << " raised by " << raise);
      CHECK(e.degree == p + raise);
      CHECK(knot_vector_problems(e.knots, e.degree, e.count()).empty());
      const auto before = knot_multiplicities(c.knots);
      const auto after = knot_multiplicities(e.knots);
      REQUIRE(before.size() == after.size());
      for (std::size_t k = 0; k < before.size(); ++k) {
        CHECK(after[k].first == before[k].first);
        CHECK(after[k].second == before[k].second + raise);
      }
      CHECK(max_distance(c, e) < 1e-13);
    }
}

TEST_CASE("degree_elevated: on a Bézier knot vector equals Bézier degree elevation", "[curves][bspline]") {
  for (int p = 1; p <= 6; ++p) {
    const BSplineCurve c = make_random_bspline(p, p + 1, 2900U + p);
    const BSplineCurve e = degree_elevated(c, p + 2);
    const BezierCurve reference = elevated(BezierCurve(c.points), p + 2);
    REQUIRE(e.count() == p + 3);
    CHECK((e.points - reference.points).cwiseAbs().maxCoeff() < 1e-14);
  }
}

TEST_CASE("greville_abscissae: reproduce the parameter (linear precision)", "[curves][bspline]") {
  for (int p = 1; p <= 5; ++p) {
    BSplineCurve c = make_random_bspline(p, p + 9, 3300U + p, -1.0, 2.0);
    const Eigen::VectorXd xi = greville_abscissae(c);
    CHECK(xi(0) == c.start());
    CHECK(xi(xi.size() - 1) == c.end());
    for (Eigen::Index i = 1; i < xi.size(); ++i) CHECK(xi(i) >= xi(i - 1));
    c.points.col(0) = xi;
    for (double t : parameters(c)) CHECK(std::abs(evaluate(c, t)(0) - t) < 1e-14);
  }
}

TEST_CASE("reparametrised (B-spline): the same points at the mapped parameters", "[curves][bspline]") {
  const BSplineCurve c = make_random_bspline(3, 9, 3700U, -1.0, 2.0);
  const BSplineCurve r = reparametrised(c, 0.0, 1.0);
  CHECK(r.start() == 0.0);
  CHECK(r.end() == 1.0);
  CHECK(knot_vector_problems(r.knots, 3, r.count()).empty());
  for (int k = 0; k <= 100; ++k) {
    const double s = k / 100.0;
    CHECK((evaluate(r, s) - evaluate(c, -1.0 + 3.0 * s)).norm() < 1e-14);
  }
}
