#include "bezier_fit.h"

#include <algorithm>
#include <cassert>

#include <Eigen/QR>

#include "coons/metrics/bernstein.h"

namespace coons {

BezierFit fit_bezier(const Curve& c, int degree, int samples) {
  assert(degree >= 1);
  if (samples <= 0) samples = std::max(10 * (degree + 1), 101);
  BezierFit fit;
  fit.samples = samples;
  if (c.bezier() && c.bezier()->degree() <= degree) {
    fit.curve = elevated(*c.bezier(), degree);  // exact: nothing to fit
    return fit;
  }
  const Eigen::RowVector3d first = c.at(0), last = c.at(1);
  Eigen::MatrixX3d P(degree + 1, 3);
  P.row(0) = first;
  P.row(degree) = last;
  if (degree >= 2) {
    Eigen::MatrixXd A(samples, degree - 1);
    Eigen::MatrixX3d rhs(samples, 3);
    for (int k = 0; k < samples; ++k) {
      const double s = double(k) / (samples - 1);
      const Eigen::VectorXd B = bernstein_basis(degree, s);
      A.row(k) = B.segment(1, degree - 1).transpose();
      rhs.row(k) = c.at(s) - B(0) * first - B(degree) * last;
    }
    P.middleRows(1, degree - 1) = A.colPivHouseholderQr().solve(rhs);
  }
  fit.curve = BezierCurve(P);
  const int check = 10 * samples + 1;
  for (int k = 0; k < check; ++k) {
    const double s = double(k) / (check - 1);
    const double d = (evaluate(fit.curve, s) - c.at(s)).norm();
    if (d > fit.max_deviation || !(d == d)) {
      fit.max_deviation = d;
      fit.at = s;
    }
  }
  return fit;
}

}  // namespace coons
