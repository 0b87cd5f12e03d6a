#include "surface_fixtures.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace coons::test {

BezierCurve make_random_bezier(int degree, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  Eigen::MatrixX3d P(degree + 1, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (int c = 0; c < 3; ++c) P(i, c) = U(rng);
  return BezierCurve(P);
}

BoundaryCurves make_random_boundary_curves(int m, int n, std::uint32_t seed) {
  BezierCurve bottom = make_random_bezier(m, seed), top = make_random_bezier(m, seed + 1000);
  BezierCurve left = make_random_bezier(n, seed + 2000), right = make_random_bezier(n, seed + 3000);
  left.points.row(0) = bottom.points.row(0);
  right.points.row(0) = bottom.points.row(m);
  left.points.row(n) = top.points.row(0);
  right.points.row(n) = top.points.row(m);
  return BoundaryCurves{bottom, top, left, right};
}

Curve closed_form_curve(std::function<Eigen::RowVector3d(double)> f, std::function<Eigen::RowVector3d(double)> df,
                        std::function<Eigen::RowVector3d(double)> d2f) {
  auto value = [f = std::move(f), df = std::move(df), d2f = std::move(d2f)](int r, double s) -> Eigen::RowVector3d {
    if (r == 0) return f(s);
    if (r == 1) return df(s);
    if (r == 2) return d2f(s);
    return Eigen::RowVector3d::Constant(std::nan(""));
  };
  return FunctionCurve{std::move(value), "closed form"};
}

double hermite(int i, double t, int r) {
  static const double c[4][4] = {{1, 0, -3, 2}, {0, 0, 3, -2}, {0, 1, -2, 1}, {0, 0, -1, 1}};
  double value = 0;
  for (int k = r; k <= 3; ++k) {
    double factor = 1;
    for (int d = 0; d < r; ++d) factor *= k - d;
    value += c[i][k] * factor * std::pow(t, k - r);
  }
  return value;
}

double max_distance(const std::function<Eigen::RowVector3d(double, double)>& a,
                    const std::function<Eigen::RowVector3d(double, double)>& b, int n) {
  double worst = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = double(i) / (n - 1), v = double(j) / (n - 1);
      worst = std::max(worst, (a(u, v) - b(u, v)).norm());
    }
  return worst;
}

std::string surface_data(const std::string& name) { return std::string(COONS_DATA_DIR) + "/surfaces/" + name; }

}  // namespace coons::test
