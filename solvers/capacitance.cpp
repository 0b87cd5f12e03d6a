#include "capacitance.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

namespace coons::solvers::detail {

void Capacitance::prepare(int rows, unsigned planning) {
  if (sine_rows_.size() != rows) sine_rows_ = SineTransform(rows, planning);
}

namespace {

// min |λ| and max |λ| over the modes y_q = cos(qπ/(n+1)), 1 ≤ q ≤ n, of one row λ(y) = a + b·y:
// λ is monotone in q, so the largest is at an end and the smallest at an end or next to the root.
std::pair<double, double> row_range(double a, double b, int n) {
  auto at = [&](int q) { return std::abs(a + b * std::cos(M_PI * q / (n + 1))); };
  double lo = std::min(at(1), at(n));
  const double hi = std::max(at(1), at(n));
  if (b != 0 && std::abs(a / b) < 1) {
    const int q = int(std::acos(-a / b) * (n + 1) / M_PI);
    for (int r : {q, q + 1})
      if (r >= 1 && r <= n) lo = std::min(lo, at(r));
  }
  return {lo, hi};
}

}  // namespace

bool Capacitance::factor(const GridStencil& s, const std::vector<double>& y,
                         const std::vector<std::vector<double>>& sine_extra) {
  R_ = s.rows;
  L_ = int(y.size());
  const int k = int(sine_extra.size());
  extra_ = k;
  inverse_.assign(std::size_t(R_), Eigen::MatrixXd());
  std::vector<double> inv(static_cast<std::size_t>(L_));
  double largest = 0, smallest = HUGE_VAL, real_smallest = HUGE_VAL, real_largest = 0;
  bool positive = false, negative = false;
  for (int p = 0; p < R_; ++p) {
    const double x = std::cos(M_PI * (p + 1) / (R_ + 1));
    const double a = s.center + 2 * s.edge_i * x, b = 2 * s.edge_j + 4 * s.diag * x;
    const auto [lo, hi] = row_range(a, b, L_ - k);
    real_smallest = std::min(real_smallest, lo);
    real_largest = std::max(real_largest, hi);
    for (int q = 0; q < L_; ++q) {
      const double lambda = a + b * y[std::size_t(q)];
      largest = std::max(largest, std::abs(lambda));
      smallest = std::min(smallest, std::abs(lambda));
      (lambda > 0 ? positive : negative) = true;
      inv[std::size_t(q)] = lambda;
    }
    if (positive && negative) return false;
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
  // The widened operator's condition over the real one's.
  return (largest / smallest) <= kMaxWideningLoss * (real_largest / real_smallest);
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
