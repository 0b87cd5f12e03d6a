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
    const double t2 = double(i) * (i - 1) / kk1;              // Bernstein coefficients of t²
    const double t3 = double(i) * (i - 1) * (i - 2) / kk2;    // and of t³
    w[i] = 1.0 - 3.0 * t2 + 2.0 * t3;
  }
  return w;
}

ControlNet boolean_sum_net(const Boundary& b, const std::vector<double>& w_u,
                           const std::vector<double>& w_v) {
  const int m = b.m, n = b.n;
  assert(int(w_u.size()) == m + 1 && int(w_v.size()) == n + 1);
  ControlNet net(m, n);
  const Eigen::RowVector3d c00 = b.bottom.row(0), c10 = b.bottom.row(m);
  const Eigen::RowVector3d c01 = b.top.row(0), c11 = b.top.row(m);
  for (int i = 0; i <= m; ++i) {
    const double a = w_u[i], abar = 1.0 - a;
    const Eigen::RowVector3d bot = b.bottom.row(i), top = b.top.row(i);
    // The part that depends on i only: corners blended along u.
    const Eigen::RowVector3d corner0 = a * c00 + abar * c10, corner1 = a * c01 + abar * c11;
    for (int j = 0; j <= n; ++j) {
      const double c = w_v[j], cbar = 1.0 - c;
      net.at(i, j) = c * (bot - corner0) + cbar * (top - corner1) + a * b.left.row(j) +
                     abar * b.right.row(j);
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
