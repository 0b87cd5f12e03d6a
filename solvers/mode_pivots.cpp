#include "mode_pivots.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "row_kernels.h"

namespace coons::solvers::detail {

bool ModePivots::factor(const GridStencil& s, const std::vector<double>& y) {
  R_ = s.rows;
  L_ = int(y.size());
  if (off_.size() != std::size_t(L_)) {
    off_ = AlignedBuffer(std::size_t(L_));
    multipliers_ = AlignedBuffer(std::size_t(L_));
    pivots_ = AlignedBuffer(std::size_t(L_));
  }
  const std::size_t L = std::size_t(L_);
  std::vector<double> diag(L), m(L), smallest(L, HUGE_VAL);
  std::vector<char> positive(L, 0), negative(L, 0), converged(L, 0);
  double* o = off_.data();
  int first = 0;  // the mode expected to converge first: the most diagonally dominant one
  double best = -1;
  for (std::size_t q = 0; q < L; ++q) {
    o[q] = s.edge_i + 2 * s.diag * y[q];
    diag[q] = s.center + 2 * s.edge_j * y[q];
    m[q] = diag[q];
    const double dominance = o[q] == 0 ? HUGE_VAL : std::abs(diag[q] / o[q]);
    if (dominance > best) {
      best = dominance;
      first = int(q);
    }
  }
  std::array<std::vector<double>, 2> r{std::vector<double>(L), std::vector<double>(L)};
  auto track = [&](std::size_t q) {
    smallest[q] = std::min(smallest[q], std::abs(m[q]));
    (m[q] > 0 ? positive : negative)[q] = 1;
  };
  for (std::size_t q = 0; q < L; ++q) {
    r[0][q] = 1 / m[q];
    track(q);
  }
  pivot_lo_.assign(std::size_t(R_), 0);
  pivot_hi_.assign(std::size_t(R_), L_);
  pivot_offset_.assign(std::size_t(R_) + 1, 0);
  pivot_values_.clear();
  int lo = L_, hi = L_;  // the modes still computed: [0, lo) ∪ [hi, L)
  // Row k is stored once the modes that converged by row k are known (after row k+1).
  auto store = [&](int k, const std::vector<double>& row) {
    if (converged[std::size_t(first)]) {
      if (lo == L_) lo = hi = first, ++hi;
      while (lo > 0 && converged[std::size_t(lo - 1)]) --lo;
      while (hi < L_ && converged[std::size_t(hi)]) ++hi;
    }
    pivot_lo_[std::size_t(k)] = lo;
    pivot_hi_[std::size_t(k)] = hi;
    pivot_values_.insert(pivot_values_.end(), row.begin(), row.begin() + lo);
    pivot_values_.insert(pivot_values_.end(), row.begin() + hi, row.end());
    pivot_offset_[std::size_t(k) + 1] = pivot_values_.size();
  };
  for (int i = 1; i < R_; ++i) {
    const std::vector<double>& before = r[std::size_t((i - 1) % 2)];
    std::vector<double>& now = r[std::size_t(i % 2)];
    auto step = [&](int q0, int q1) {
      for (int q = q0; q < q1; ++q) {
        const std::size_t k = std::size_t(q);
        const double next = diag[k] - o[k] * o[k] * before[k];
        if (next == m[k]) converged[k] = 1;
        m[k] = next;
        now[k] = 1 / next;
        track(k);
      }
    };
    step(0, lo);
    step(hi, L_);
    store(i - 1, before);
  }
  const std::vector<double>& last = r[std::size_t((R_ - 1) % 2)];
  store(R_ - 1, last);
  // Converged modes hold the same value in both rows of r.
  pivot_limit_.assign(last.begin(), last.end());
  for (std::size_t q = 0; q < L; ++q) {
    const double scale = std::abs(diag[q]) + 2 * std::abs(o[q]);
    if (!(smallest[q] > kZeroPivot * scale)) return false;
    if (positive[q] && negative[q] && smallest[q] < kUnsafePivot * scale) return false;
  }
  return true;
}

void ModePivots::load(int from, int to) { load(from, to, 0, L_); }

void ModePivots::load(int from, int to, int q0, int q1) {
  const double* o = off_.data();
  double* r = pivots_.data();
  double* l = multipliers_.data();
  const double* row = pivot_values_.data() + pivot_offset_[std::size_t(to)];
  const int lo = pivot_lo_[std::size_t(to)], hi = pivot_hi_[std::size_t(to)];
  auto value = [&](int q) { return q < lo ? row[q] : q >= hi ? row[lo + q - hi] : pivot_limit_[std::size_t(q)]; };
  if (from < 0) {  // the whole row
    for (int q = q0; q < q1; ++q) r[q] = value(q);
    multiply(o + q0, r + q0, l + q0, q1 - q0);
    return;
  }
  // Modes in [a, b) are converged in both rows: they keep their values.
  const int a = std::clamp(std::max(lo, pivot_lo_[std::size_t(from)]), q0, q1);
  const int b = std::clamp(std::min(hi, pivot_hi_[std::size_t(from)]), a, q1);
  for (int q = q0; q < a; ++q) r[q] = value(q);
  for (int q = b; q < q1; ++q) r[q] = value(q);
  multiply(o + q0, r + q0, l + q0, a - q0);
  multiply(o + b, r + b, l + b, q1 - b);
}

}  // namespace coons::solvers::detail
