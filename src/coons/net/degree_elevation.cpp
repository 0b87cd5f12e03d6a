#include "degree_elevation.h"

#include <cassert>

namespace coons {

Eigen::MatrixX3d elevate_curve(const Eigen::MatrixX3d& P, int degree) {
  assert(degree >= P.rows() - 1);
  Eigen::MatrixX3d Q = P;
  for (int k = int(P.rows()) - 1; k < degree; ++k) {  // k → k + 1
    Eigen::MatrixX3d R(k + 2, 3);
    R.row(0) = Q.row(0);
    R.row(k + 1) = Q.row(k);
    for (int i = 1; i <= k; ++i) {
      const double a = double(i) / (k + 1);
      // Q_i + a (Q_{i−1} − Q_i) rather than a Q_{i−1} + (1 − a) Q_i: equal neighbours stay equal
      // bit for bit (a constant side, a side in a coordinate plane).
      R.row(i) = Q.row(i) + a * (Q.row(i - 1) - Q.row(i));
    }
    Q = std::move(R);
  }
  return Q;
}

Boundary elevate_boundary(const Boundary& b, int m, int n) {
  Boundary out = b;
  out.m = m;
  out.n = n;
  out.bottom = elevate_curve(b.bottom, m);
  out.top = elevate_curve(b.top, m);
  out.left = elevate_curve(b.left, n);
  out.right = elevate_curve(b.right, n);
  return out;
}

}  // namespace coons
