#include "capacitance.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace coons::solvers::detail {

int largest_prime_factor(int n) {
  int largest = 1;
  for (int f = 2; f * f <= n; ++f)
    while (n % f == 0) {
      largest = f;
      n /= f;
    }
  return std::max(largest, n);
}

namespace {

// A real FFT length m = n + 1 for which the sine transform of length n is fast: FFTW has codelets
// for the factors up to 13 and falls back to slower generic ones above; an odd length is 2.5–4×
// slower than an even one nearby (1029 = 3·7³ against 1024 or 1000), which matters from a few
// hundred columns on.
bool fast_length(int m) { return largest_prime_factor(m) <= 13 && (m % 2 == 0 || m < 256); }

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

int interface_columns(int cols) {
  if (cols < 8 || fast_length(cols + 1)) return 0;
  for (int k = 1; k <= kMaxInterface && cols - k >= 2; ++k)
    if (fast_length(cols - k + 1)) return k;
  return 0;
}

void Capacitance::prepare(int rows, unsigned planning) {
  if (sine_rows_.size() != rows) sine_rows_ = SineTransform(rows, planning);
}

bool Capacitance::factor(const GridStencil& s, const std::vector<double>& y) {
  R_ = s.rows;
  L_ = int(y.size());
  k_ = s.cols - L_;
  edge_j_ = s.edge_j;
  diag_ = s.diag;
  pivots_.assign(std::size_t(R_) * std::size_t(std::max(k_, 0)), 0.0);
  c1_.assign(std::size_t(R_), 0.0);
  if (k_ < 1 || L_ < 1) return false;
  // S(L−1, q)² = sin²((q+1)π/(L+1)), the same for every p, and the modes y_q
  const Eigen::ArrayXd sine2 = Eigen::ArrayXd::LinSpaced(L_, 1, L_).unaryExpr(
      [&](double q) { return std::pow(std::sin(M_PI * q / (L_ + 1)), 2); });
  const Eigen::ArrayXd modes = Eigen::Map<const Eigen::ArrayXd>(y.data(), L_);
  double largest = 0, smallest = HUGE_VAL, real_smallest = HUGE_VAL, real_largest = 0;
  bool positive = false, negative = false;
  for (int p = 0; p < R_; ++p) {
    const double x = std::cos(M_PI * (p + 1) / (R_ + 1));
    const double a = s.center + 2 * s.edge_i * x, c1 = s.edge_j + 2 * s.diag * x;
    const auto [lo, hi] = row_range(a, 2 * c1, s.cols);
    real_smallest = std::min(real_smallest, lo);
    real_largest = std::max(real_largest, hi);
    // λ_pq is monotone in q (y_q is): its extremes are at the two ends
    for (const double lambda : {a + 2 * c1 * y.front(), a + 2 * c1 * y.back()}) {
      largest = std::max(largest, std::abs(lambda));
      smallest = std::min(smallest, std::abs(lambda));
      (lambda > 0 ? positive : negative) = true;
    }
    if (positive && negative) return false;
    // (T_p⁻¹)_{L−1,L−1}, in Eigen's vectorised division and sum
    const double g = 2.0 / (L_ + 1) * (sine2 / (a + 2 * c1 * modes)).sum();
    // S_p = LDLᵀ without pivoting (tridiagonal): pivots m_0 = a − c1²g, m_j = a − c1²/m_{j−1}. S_p
    // is definite when the fast region and the grid are; a pivot below kInterfacePivot relative to
    // the row declines (the exact fallback takes the grid then).
    double* m = pivots_.data() + std::size_t(p) * std::size_t(k_);
    for (int j = 0; j < k_; ++j) {
      m[j] = j == 0 ? a - c1 * c1 * g : a - c1 * c1 / m[j - 1];
      if (!(std::abs(m[j]) > kInterfacePivot * (std::abs(a) + 2 * std::abs(c1)))) return false;
    }
    c1_[std::size_t(p)] = c1;
  }
  if (!(smallest > kZeroPivot * largest)) return false;
  // The fast region's condition over the real grid's.
  return (largest / smallest) <= kMaxNarrowingLoss * (real_largest / real_smallest);
}

void Capacitance::interface_values(const std::vector<double>& V, const std::vector<double>& b_interface,
                                   std::vector<double>& x_interface) {
  const std::size_t k = std::size_t(k_), R = std::size_t(R_);
  std::vector<double> column(R), v_hat(R), hat(R * k);
  sine_rows_.apply(V.data(), v_hat.data(), 1.0);
  for (std::size_t m = 0; m < k; ++m) {
    for (std::size_t i = 0; i < R; ++i) column[i] = b_interface[i * k + m];
    sine_rows_.apply(column.data(), column.data(), 1.0);
    for (std::size_t p = 0; p < R; ++p) hat[p * k + m] = column[p];
  }
  for (std::size_t p = 0; p < R; ++p) {  // S_p x̃ = b̃_I − c1_p Ṽ e₁, by the pivots of factor()
    double* x = hat.data() + p * k;
    const double* m = pivots_.data() + p * k;
    const double c1 = c1_[p];
    x[0] -= c1 * v_hat[p];
    for (std::size_t j = 1; j < k; ++j) x[j] -= c1 / m[j - 1] * x[j - 1];
    x[k - 1] /= m[k - 1];
    for (std::size_t j = k - 1; j-- > 0;) x[j] = (x[j] - c1 * x[j + 1]) / m[j];
  }
  x_interface.assign(R * k, 0.0);
  for (std::size_t m = 0; m < k; ++m) {
    for (std::size_t p = 0; p < R; ++p) column[p] = hat[p * k + m];
    sine_rows_.apply(column.data(), column.data(), 2.0 / (R_ + 1));
    for (std::size_t i = 0; i < R; ++i) x_interface[i * k + m] = column[i];
  }
}

void Capacitance::coupling(const std::vector<double>& x_interface, std::vector<double>& delta) const {
  const std::size_t k = std::size_t(k_), R = std::size_t(R_);
  delta.assign(R, 0.0);
  for (std::size_t i = 0; i < R; ++i) {
    const double up = i > 0 ? x_interface[(i - 1) * k] : 0.0, down = i + 1 < R ? x_interface[(i + 1) * k] : 0.0;
    delta[i] = edge_j_ * x_interface[i * k] + diag_ * (up + down);
  }
}

}  // namespace coons::solvers::detail
