#include "bezier_curve.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "coons/net/degree_elevation.h"

namespace coons {

Eigen::RowVector3d bernstein_sum(const Eigen::MatrixX3d& P, double t) {
  return bernstein_basis(int(P.rows()) - 1, t).transpose() * P;
}

Eigen::RowVector3d evaluate(const BezierCurve& c, double t) {
  if (c.degree() > kDeCasteljauMaxDegree && t >= 0 && t <= 1) return bernstein_sum(c.points, t);
  Eigen::MatrixX3d Q = c.points;
  for (int k = c.degree(); k >= 1; --k)
    for (int i = 0; i < k; ++i) Q.row(i) = (1 - t) * Q.row(i) + t * Q.row(i + 1);
  return Q.row(0);
}

Eigen::MatrixX3d hodograph(const Eigen::MatrixX3d& P, int r) {
  const int k = int(P.rows()) - 1;
  if (r > k) return Eigen::MatrixX3d::Zero(1, 3);
  Eigen::MatrixX3d Q = P;
  double factor = 1;
  for (int d = 0; d < r; ++d) {
    factor *= k - d;
    Q = (Q.bottomRows(Q.rows() - 1) - Q.topRows(Q.rows() - 1)).eval();
  }
  return factor * Q;
}

Eigen::RowVector3d evaluate_derivative(const BezierCurve& c, int r, double t) {
  assert(r >= 0);
  if (r == 0) return evaluate(c, t);
  return evaluate(BezierCurve(hodograph(c.points, r)), t);
}

BezierCurve elevated(const BezierCurve& c, int degree) { return BezierCurve(elevate_curve(c.points, degree)); }

Eigen::RowVector3d blossom(const BezierCurve& c, const std::vector<double>& args) {
  assert(int(args.size()) == c.degree());
  Eigen::MatrixX3d Q = c.points;
  for (int k = c.degree(), a = 0; k >= 1; --k, ++a) {
    const double t = args[a];
    for (int i = 0; i < k; ++i) Q.row(i) = (1 - t) * Q.row(i) + t * Q.row(i + 1);
  }
  return Q.row(0);
}

BezierCurve reparametrised(const BezierCurve& c, double t1, double t2) {
  const int k = c.degree();
  Eigen::MatrixX3d P(k + 1, 3);
  for (int i = 0; i <= k; ++i) {
    std::vector<double> args(k, t1);
    for (int a = 0; a < i; ++a) args[k - 1 - a] = t2;  // k − i copies of t₁, i copies of t₂
    P.row(i) = blossom(c, args);
  }
  return BezierCurve(P);
}

std::pair<BezierCurve, BezierCurve> subdivide(const BezierCurve& c, double t) {
  // de Casteljau's triangle: its left edge is the first half, its right edge the second.
  const int k = c.degree();
  Eigen::MatrixX3d Q = c.points, first(k + 1, 3), second(k + 1, 3);
  first.row(0) = Q.row(0);
  second.row(k) = Q.row(k);
  for (int level = 1; level <= k; ++level) {
    for (int i = 0; i <= k - level; ++i) Q.row(i) = (1 - t) * Q.row(i) + t * Q.row(i + 1);
    first.row(level) = Q.row(0);
    second.row(k - level) = Q.row(k - level);
  }
  return {BezierCurve(first), BezierCurve(second)};
}

}  // namespace coons
