#include "capacitance.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace coons::solvers::detail {

void Capacitance::prepare(int rows, unsigned planning) {
  if (sine_rows_.size() != rows) sine_rows_ = SineTransform(rows, planning);
}

bool Capacitance::factor(const GridStencil& s, const std::vector<double>& y,
                         const std::vector<std::vector<double>>& sine_extra) {
  R_ = s.rows;
  L_ = int(y.size());
  const int k = int(sine_extra.size());
  extra_ = k;
  inverse_.assign(std::size_t(R_), Eigen::MatrixXd());
  std::vector<double> inv(static_cast<std::size_t>(L_));
  double largest = 0;
  for (int p = 0; p < R_; ++p) {
    const double x = std::cos(M_PI * (p + 1) / (R_ + 1));
    const double a = s.center + 2 * s.edge_i * x, b = 2 * s.edge_j + 4 * s.diag * x;
    for (int q = 0; q < L_; ++q) {
      const double lambda = a + b * y[std::size_t(q)];
      largest = std::max(largest, std::abs(lambda));
      inv[std::size_t(q)] = lambda;
    }
    for (int q = 0; q < L_; ++q) inv[std::size_t(q)] = 1 / inv[std::size_t(q)];
    Eigen::MatrixXd G(k, k);
    for (int m = 0; m < k; ++m)
      for (int n = 0; n <= m; ++n) {
        double sum = 0;
        const double* sm = sine_extra[std::size_t(m)].data();
        const double* sn = sine_extra[std::size_t(n)].data();
        for (int q = 0; q < L_; ++q) sum += sm[q] * sn[q] * inv[std::size_t(q)];
        G(m, n) = G(n, m) = 2.0 / (L_ + 1) * sum;
      }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
    if (!lu.isInvertible()) return false;
    inverse_[std::size_t(p)] = lu.inverse();
    for (int q = 0; q < L_; ++q)
      if (!(std::abs(1 / inv[std::size_t(q)]) > kZeroPivot * largest)) return false;
  }
  return true;
}

void Capacitance::sources(const std::vector<double>& V, std::vector<double>& U) {
  const std::size_t k = std::size_t(extra_), R = std::size_t(R_);
  std::vector<double> column(R), hat(R * k);
  for (std::size_t m = 0; m < k; ++m) {
    for (std::size_t i = 0; i < R; ++i) column[i] = V[i * k + m];
    sine_rows_.apply(column.data(), column.data(), 1.0);
    for (std::size_t p = 0; p < R; ++p) hat[p * k + m] = column[p];
  }
  U.assign(R * k, 0.0);
  for (std::size_t p = 0; p < R; ++p) {
    const Eigen::Map<const Eigen::VectorXd> vp(hat.data() + p * k, Eigen::Index(k));
    const Eigen::VectorXd up = -(inverse_[p] * vp);
    for (std::size_t m = 0; m < k; ++m) hat[p * k + m] = up(Eigen::Index(m));
  }
  for (std::size_t m = 0; m < k; ++m) {
    for (std::size_t p = 0; p < R; ++p) column[p] = hat[p * k + m];
    sine_rows_.apply(column.data(), column.data(), 2.0 / (R_ + 1));
    for (std::size_t i = 0; i < R; ++i) U[i * k + m] = column[i];
  }
}

}  // namespace coons::solvers::detail
