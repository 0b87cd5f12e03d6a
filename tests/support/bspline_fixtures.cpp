#include "support/bspline_fixtures.h"

#include <algorithm>
#include <random>
#include <vector>

#include "support/fixtures.h"

namespace coons::test {

Eigen::VectorXd make_random_knots(int degree, int count, std::uint32_t seed, double a, double b) {
  std::mt19937 rng(seed);
  const int steps = 4 * count + 8;
  std::uniform_int_distribution<int> grid(1, steps - 1);
  const int interior = count - degree - 1;
  std::vector<int> chosen;
  while (int(chosen.size()) < interior) {
    const int k = grid(rng);
    if (std::count(chosen.begin(), chosen.end(), k) < degree) chosen.push_back(k);
  }
  std::sort(chosen.begin(), chosen.end());
  Eigen::VectorXd U(count + degree + 1);
  for (int i = 0; i <= degree; ++i) {
    U(i) = a;
    U(U.size() - 1 - i) = b;
  }
  for (int i = 0; i < interior; ++i) U(degree + 1 + i) = a + (b - a) * double(chosen[std::size_t(i)]) / steps;
  return U;
}

BSplineSurface make_random_bspline_surface(int p, int count_u, int q, int count_v, std::uint32_t seed, double u0,
                                           double u1, double v0, double v1) {
  BSplineSurface s;
  s.degree_u = p;
  s.degree_v = q;
  s.knots_u = make_random_knots(p, count_u, seed, u0, u1);
  s.knots_v = make_random_knots(q, count_v, seed + 1, v0, v1);
  s.net = make_random_net(count_u - 1, count_v - 1, seed + 2);
  return s;
}

BSplineCurve make_random_bspline(int degree, int count, std::uint32_t seed, double a, double b) {
  std::mt19937 rng(seed + 7919U);
  std::uniform_real_distribution<double> X(-1, 1);
  Eigen::MatrixX3d P(count, 3);
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) P(i, c) = X(rng);
  return {degree, make_random_knots(degree, count, seed, a, b), P};
}

Eigen::VectorXd bezier_knots(int degree, double a, double b) {
  Eigen::VectorXd U(2 * degree + 2);
  U.head(degree + 1).setConstant(a);
  U.tail(degree + 1).setConstant(b);
  return U;
}

BSplineBoundary make_random_bspline_boundary(int p, int count_u, int q, int count_v, std::uint32_t seed) {
  BSplineBoundary b{make_random_bspline(p, count_u, seed, 0.0, 1.0),
                    make_random_bspline(p + 1, count_u + 2, seed + 1000, -1.0, 2.0),
                    make_random_bspline(q, count_v, seed + 2000, 0.5, 3.0),
                    make_random_bspline(q, count_v + 1, seed + 3000, 0.0, 1.0)};
  b.left.points.row(0) = b.bottom.points.row(0);
  b.right.points.row(0) = b.bottom.points.row(b.bottom.count() - 1);
  b.left.points.row(b.left.count() - 1) = b.top.points.row(0);
  b.right.points.row(b.right.count() - 1) = b.top.points.row(b.top.count() - 1);
  return b;
}

}  // namespace coons::test
