#include "coons_net.h"

#include <cassert>

namespace coons {

std::vector<double> linear_blend_weights(int k) {
  std::vector<double> w(k + 1);
  for (int i = 0; i <= k; ++i) w[i] = 1.0 - double(i) / k;
  return w;
}

std::vector<double> hermite_blend_weights(int k) {
  assert(k >= 3);
  std::vector<double> w(k + 1);
  const double kk1 = double(k) * (k - 1), kk2 = kk1 * (k - 2);
  for (int i = 0; i <= k; ++i) {
    const double t2 = double(i) * (i - 1) / kk1;            // Bernstein coefficients of t²
    const double t3 = double(i) * (i - 1) * (i - 2) / kk2;  // and of t³
    w[i] = 1.0 - 3.0 * t2 + 2.0 * t3;
  }
  return w;
}

ControlNet boolean_sum_net(const Boundary& b, const std::vector<double>& w_u, const std::vector<double>& w_v) {
  const int m = b.m, n = b.n;
  assert(int(w_u.size()) == m + 1 && int(w_v.size()) == n + 1);
  ControlNet net;
  net.m = m;
  net.n = n;
  net.points.resize(Eigen::Index(m + 1) * (n + 1), 3);  // every entry is written below, once
  const Eigen::Map<const Eigen::ArrayXd> cv(w_v.data(), n + 1);
  for (int c = 0; c < 3; ++c) {
    const Eigen::ArrayXd left = b.left.col(c).array(), right = b.right.col(c).array();
    const double c00 = b.bottom(0, c), c10 = b.bottom(m, c), c01 = b.top(0, c), c11 = b.top(m, c);
    double* out = net.points.col(c).data();
    for (int i = 0; i <= m; ++i) {
      const double a = w_u[i], abar = 1.0 - a;
      // b[i][j] = c_j (bottom_i − corner0_i) + (1 − c_j)(top_i − corner1_i) + a left_j + ā right_j
      const double lo = b.bottom(i, c) - (a * c00 + abar * c10);
      const double hi = b.top(i, c) - (a * c01 + abar * c11);
      Eigen::Map<Eigen::ArrayXd> row(out + Eigen::Index(i) * (n + 1), n + 1);
      row = hi + cv * (lo - hi) + a * left + abar * right;
    }
  }
  // The formula reproduces the frame up to rounding; store the frame exactly.
  for (int i = 0; i <= m; ++i) {
    net.at(i, 0) = b.bottom.row(i);
    net.at(i, n) = b.top.row(i);
  }
  for (int j = 1; j < n; ++j) {
    net.at(0, j) = b.left.row(j);
    net.at(m, j) = b.right.row(j);
  }
  return net;
}

ControlNet discrete_coons_net(const Boundary& b) {
  return boolean_sum_net(b, linear_blend_weights(b.m), linear_blend_weights(b.n));
}

ControlNet hermite_coons_net(const Boundary& b) {
  return boolean_sum_net(b, hermite_blend_weights(b.m), hermite_blend_weights(b.n));
}

}  // namespace coons
