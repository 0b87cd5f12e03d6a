#include "kronecker_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "row_kernels.h"

namespace coons::solvers::detail {

bool KroneckerSolve::applies(const GridStencil& s) {
  if (s.center == 0) return false;
  const double cd = s.center * s.diag, ee = s.edge_i * s.edge_j;
  return std::abs(cd - ee) <= 4 * std::numeric_limits<double>::epsilon() * (std::abs(cd) + std::abs(ee));
}

bool KroneckerSolve::factor(const GridStencil& s) {
  R_ = s.rows;
  C_ = s.cols;
  if (!ti_.factor(R_, 1.0, s.edge_i / s.center) || !tj_.factor(C_, s.center, s.edge_j)) return false;
  std::vector<double> unit(std::size_t(C_), 0.0);
  tj_e0_.assign(std::size_t(C_), 0.0);
  tj_e1_.assign(std::size_t(C_), 0.0);
  unit[0] = 1;
  tj_.solve(unit.data(), tj_e0_.data());
  if (C_ >= 2) {
    unit[0] = 0;
    unit[std::size_t(C_ - 1)] = 1;
    tj_.solve(unit.data(), tj_e1_.data());
  }
  y_.assign(std::size_t(C_), 0.0);
  return true;
}

void KroneckerSolve::solve(const RowForm& f, const double* b, double* x) {
  if (int(f.dense_rows.size()) <= kMaxRank)
    solve_rank(f, x);
  else
    solve_dense(b, x);
}

void KroneckerSolve::solve_rank(const RowForm& f, double* x) {
  const int K = 2 + int(f.dense_rows.size());
  u_.assign(std::size_t(K) * std::size_t(R_), 0.0);
  v_.assign(std::size_t(K) * std::size_t(C_), 0.0);
  auto u = [&](int k) { return u_.data() + std::size_t(k) * std::size_t(R_); };
  auto v = [&](int k) { return v_.data() + std::size_t(k) * std::size_t(C_); };
  ti_.solve(f.first.data(), u(0));
  ti_.solve(f.last.data(), u(1));
  std::copy(tj_e0_.begin(), tj_e0_.end(), v(0));
  std::copy(tj_e1_.begin(), tj_e1_.end(), v(1));
  for (int k = 2; k < K; ++k) {
    const int r = f.dense_rows[std::size_t(k - 2)];
    u(k)[r] = 1;
    ti_.solve(u(k), u(k));
    tj_.solve(f.values.data() + std::size_t(k - 2) * std::size_t(C_), v(k));
  }
  std::vector<const double*> vs(static_cast<std::size_t>(K));
  std::vector<double> a(static_cast<std::size_t>(K));
  for (int k = 0; k < K; ++k) vs[std::size_t(k)] = v(k);
  for (int i = 0; i < R_; ++i) {
    for (int k = 0; k < K; ++k) a[std::size_t(k)] = u(k)[i];
    rank_row(a.data(), vs.data(), K, x + std::size_t(i) * std::size_t(C_), C_);
  }
}

void KroneckerSolve::solve_dense(const double* b, double* x) {
  const std::size_t C = std::size_t(C_);
  const double off = ti_.off;
  const double* r = ti_.inv_pivot.data();
  std::copy(b, b + C, x);
  for (int i = 1; i < R_; ++i)
    axpy_rows(b + std::size_t(i) * C, off * r[i - 1], x + (std::size_t(i) - 1) * C, x + std::size_t(i) * C, C_);
  double* y = y_.data();
  std::fill(y, y + C, 0.0);
  for (int i = R_ - 1; i >= 0; --i) {
    double* xi = x + std::size_t(i) * C;
    for (std::size_t j = 0; j < C; ++j) y[j] = (xi[j] - off * y[j]) * r[i];
    tj_.solve(y, xi);
  }
}

}  // namespace coons::solvers::detail
