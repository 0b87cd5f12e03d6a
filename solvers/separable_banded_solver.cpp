#include "separable_banded_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "column_fill.h"
#include "separable_outer_products.h"
#include "stencil_operator.h"
#include "vector_clones.h"

namespace coons::solvers {

namespace {

// The factors as the sweeps read them: reciprocal pivots and the two multipliers, padded so that
// l1[k−1] and l2[k−2], l2[k−1] exist (they are never used with a non-zero partner).
struct SweepFactors {
  std::vector<double> inv_d, l1, l2;
  explicit SweepFactors(const BandedLdlt& f) {
    const auto k = std::size_t(f.d.size());
    inv_d.assign(k, 0.0);
    l1.assign(k + 2, 0.0);
    l2.assign(k + 2, 0.0);
    for (std::size_t r = 0; r < k; ++r) inv_d[r] = 1 / f.d[Eigen::Index(r)];
    std::copy_n(f.l1.data(), f.l1.size(), l1.data());
    std::copy_n(f.l2.data(), f.l2.size(), l2.data());
  }
};

// Rows of the grid solved along j together: the lanes of the tile.
constexpr int kLanes = 8;
// Columns of the grid solved along i together (a strip of rows × kStrip stays in L2).
constexpr int kStrip = 128;
// How many rows ahead the forward sweep along i prefetches its strip.
constexpr int kPrefetchRows = 6;

// Q⁻¹ along j of kLanes grid rows at once: src[t] (length k) → dst[t], through the tile T
// (k × kLanes, lane-contiguous), so that the recurrences run across the lanes (vectorised) and
// the transposes are fused into the forward (reading src) and the backward sweep (writing dst).
COONS_VECTOR_CLONES void solve_lanes_along_j(const double* const* source, double* const* target,
                                             const double* __restrict inv_d, const double* __restrict l1,
                                             const double* __restrict l2, int k, double* __restrict T) {
  std::array<const double*, kLanes> src{};
  std::array<double*, kLanes> dst{};
  std::copy_n(source, kLanes, src.begin());
  std::copy_n(target, kLanes, dst.begin());
  for (int t = 0; t < kLanes; ++t) T[t] = src[std::size_t(t)][0];
  if (k > 1)
    for (int t = 0; t < kLanes; ++t) T[kLanes + t] = src[std::size_t(t)][1] - l1[0] * T[t];
  for (int j = 2; j < k; ++j) {
    const double a = l1[j - 1], b = l2[j - 2];
    double* __restrict row = T + std::ptrdiff_t(j) * kLanes;
    const double* __restrict up1 = row - kLanes;
    const double* __restrict up2 = row - 2 * kLanes;
    for (int t = 0; t < kLanes; ++t) row[t] = src[std::size_t(t)][j] - b * up2[t] - a * up1[t];
  }
  const auto store = [&](int j) {
    const double* row = T + std::ptrdiff_t(j) * kLanes;
    for (int t = 0; t < kLanes; ++t) dst[std::size_t(t)][j] = row[t];
  };
  double* __restrict last = T + std::ptrdiff_t(k - 1) * kLanes;
  for (int t = 0; t < kLanes; ++t) last[t] *= inv_d[k - 1];
  store(k - 1);
  if (k > 1) {
    double* __restrict row = last - kLanes;
    for (int t = 0; t < kLanes; ++t) row[t] = row[t] * inv_d[k - 2] - l1[k - 2] * last[t];
    store(k - 2);
  }
  for (int j = k - 3; j >= 0; --j) {
    const double s = inv_d[j], a = l1[j], b = l2[j];
    double* __restrict row = T + std::ptrdiff_t(j) * kLanes;
    const double* __restrict dn1 = row + kLanes;
    const double* __restrict dn2 = row + 2 * kLanes;
    for (int t = 0; t < kLanes; ++t) row[t] = row[t] * s - b * dn2[t] - a * dn1[t];
    store(j);
  }
}

// P⁻¹ along i of the columns [j0, j0 + w) of Y (rows × stride, row-major), in place: forward down,
// scaling and back substitution up (the strip stays in cache between the two).
COONS_VECTOR_CLONES void solve_strip_along_i(double* __restrict Y, std::ptrdiff_t stride, int rows, int w,
                                             const double* __restrict inv_d, const double* __restrict l1,
                                             const double* __restrict l2) {
  for (int r = 1; r < rows; ++r) {
    double* __restrict y = Y + r * stride;
    const double* __restrict y1 = y - stride;
    const double a = l1[r - 1];
    // The rows of a strip are a page apart, so the hardware prefetcher starts afresh on each:
    // ask for the row kPrefetchRows ahead (one line per 8 values) while this one is solved.
    if (r + kPrefetchRows < rows)
      for (int q = 0; q < w; q += 8) __builtin_prefetch(y + kPrefetchRows * stride + q, 1);
    if (r >= 2) {
      const double* __restrict y2 = y1 - stride;
      const double b = l2[r - 2];
      for (int q = 0; q < w; ++q) y[q] -= a * y1[q] + b * y2[q];
    } else {
      for (int q = 0; q < w; ++q) y[q] -= a * y1[q];
    }
  }
  for (int r = rows - 1; r >= 0; --r) {
    double* __restrict y = Y + r * stride;
    const double s = inv_d[r];
    if (r + 2 < rows) {
      const double* __restrict y1 = y + stride;
      const double* __restrict y2 = y1 + stride;
      const double a = l1[r], b = l2[r];
      for (int q = 0; q < w; ++q) y[q] = y[q] * s - a * y1[q] - b * y2[q];
    } else if (r + 1 < rows) {
      const double* __restrict y1 = y + stride;
      const double a = l1[r];
      for (int q = 0; q < w; ++q) y[q] = y[q] * s - a * y1[q];
    } else {
      for (int q = 0; q < w; ++q) y[q] *= s;
    }
  }
}

// X = P⁻¹ R Q⁻¹ for each column of B viewed as a rows × cols grid R (row-major), in two sweeps over
// the grid: Q⁻¹ on blocks of kLanes rows (reading B, writing X), then P⁻¹ on strips of kStrip columns
// (in place, forward and back within the cached strip). The units of each sweep (blocks, strips,
// over the three columns) are independent and shared among `threads`; every unit does the same
// operations whatever the thread count, so the result does not depend on it. A column of B with
// the form of separable_outer_products.h is solved as a sum of outer products instead; `forms`,
// when given, holds the outer_form() of each column (read already), else it is read here.
using ColumnForms = std::array<std::optional<detail::OuterForm>, 3>;
void solve_separable(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const Eigen::MatrixX3d& B,
                     Eigen::MatrixX3d& X, int threads, const ColumnForms* forms = nullptr) {
  X.resize(B.rows(), 3);
  if (rows == 0 || cols == 0) return;
  const SweepFactors si(fi), sj(fj);
  std::vector<int> swept;  // the columns of B not solved by outer products
  for (int c = 0; c < 3; ++c) {
    const std::optional<detail::OuterForm> form =
        forms ? (*forms)[std::size_t(c)] : detail::outer_form(B.col(c).data(), rows, cols, threads);
    if (form)
      detail::solve_outer_products(fi, fj, rows, cols, *form, B.col(c).data(), X.col(c).data(), threads);
    else
      swept.push_back(c);
  }
  if (swept.empty()) return;
  const int ncols = int(swept.size());
  const int blocks = (rows + kLanes - 1) / kLanes, strips = (cols + kStrip - 1) / kStrip;
  [[maybe_unused]] const int nt = std::max(1, threads);
#if defined(_OPENMP)
#pragma omp parallel num_threads(nt) if (nt > 1)
#endif
  {
    std::vector<double> tile(std::size_t(cols) * kLanes), zeros(std::size_t(cols), 0.0);
    std::vector<double> sink(std::size_t(cols), 0.0);
    std::array<const double*, kLanes> src{};
    std::array<double*, kLanes> dst{};
#if defined(_OPENMP)
#pragma omp for schedule(dynamic)
#endif
    for (int unit = 0; unit < ncols * blocks; ++unit) {
      const int c = swept[std::size_t(unit / blocks)], r0 = (unit % blocks) * kLanes;
      for (int t = 0; t < kLanes; ++t) {
        const bool inside = r0 + t < rows;
        const std::ptrdiff_t at = std::ptrdiff_t(r0 + t) * cols;
        src[std::size_t(t)] = inside ? B.col(c).data() + at : zeros.data();
        dst[std::size_t(t)] = inside ? X.col(c).data() + at : sink.data();
      }
      solve_lanes_along_j(src.data(), dst.data(), sj.inv_d.data(), sj.l1.data(), sj.l2.data(), cols, tile.data());
    }
#if defined(_OPENMP)
#pragma omp for schedule(dynamic)
#endif
    for (int unit = 0; unit < ncols * strips; ++unit) {
      const int c = swept[std::size_t(unit / strips)], j0 = (unit % strips) * kStrip;
      solve_strip_along_i(X.col(c).data() + j0, cols, rows, std::min(kStrip, cols - j0), si.inv_d.data(), si.l1.data(),
                          si.l2.data());
    }
  }
}

class SeparableBandedSolver final : public LinearSolver {
 public:
  SeparableBandedSolver(std::optional<SeparableBandedOperator> op, const SolverOptions& options)
      : LinearSolver(options), fixed_(op) {}

  [[nodiscard]] std::string name() const override { return "separable-banded"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    return describe(op, summary) ? SolveStatus::kSuccess : SolveStatus::kNotApplicable;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!describe(op, summary)) return SolveStatus::kNotApplicable;
    for (const auto& [diagonals, k, f, axis] :
         {std::tuple{op_.along_i, op_.rows, &fi_, "i"}, std::tuple{op_.along_j, op_.cols, &fj_, "j"}}) {
      const SolveStatus status = banded_ldlt(diagonals, k, *f);
      if (status == SolveStatus::kSingular) {
        summary.message = std::string("the factor along ") + axis + " is singular (a zero last pivot of its LDL^T)";
        return status;
      }
      if (status != SolveStatus::kSuccess) {
        summary.message = std::string("the factor along ") + axis +
                          " is indefinite (pivots of both signs or a zero pivot): LDL^T without pivoting "
                          "cannot solve it safely";
        return status;
      }
    }
    summary.factor_nnz = 3LL * (op_.rows + op_.cols);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const bool read = forms_source_ == B.data();
    forms_source_ = nullptr;
    solve_separable(fi_, fj_, op_.rows, op_.cols, B, X, resolved_threads(options_.threads), read ? &forms_ : nullptr);
    summary.iterations = 1;
    return SolveStatus::kSuccess;
  }

  // Each column's largest magnitude comes from the check of its form (outer_form), which do_solve
  // then takes over, when every column has that form; otherwise (a column to be swept, whose check
  // stopped early) from a pass of its own.
  ColumnExponents rhs_scaling(const Eigen::MatrixX3d& B) override {
    forms_source_ = nullptr;
    const int threads = resolved_threads(options_.threads);
    bool all = op_.rows > 0 && op_.cols > 0;
    for (std::size_t c = 0; c < 3 && all; ++c) {
      forms_[c] = detail::outer_form(B.col(Eigen::Index(c)).data(), op_.rows, op_.cols, threads);
      all = forms_[c].has_value();
    }
    if (!all) return LinearSolver::rhs_scaling(B);
    ColumnExponents e{};
    for (std::size_t c = 0; c < 3; ++c) e[c] = scaling_exponent(forms_[c]->largest);
    forms_source_ = B.data();
    return e;
  }

 private:
  // op_ = the operator given at construction, else the one read from op; false (with the reason
  // in the summary) when there is none or its size differs from op's.
  bool describe(const LinearOperator& op, SolveSummary& summary) {
    if (fixed_) {
      op_ = *fixed_;
    } else if (auto found = separable_operator(op)) {
      op_ = *found;
    } else {
      summary.message =
          "needs a separable stencil (w(a,b) = u(a) v(b), symmetric) on a full rectangle (a grid stencil or "
          "grid operator)";
      return false;
    }
    if (op.size() != op_.size()) {
      summary.message = "the operator has " + std::to_string(op.size()) + " unknowns, the separable grid " +
                        std::to_string(op_.rows) + " x " + std::to_string(op_.cols);
      return false;
    }
    return true;
  }

  std::optional<SeparableBandedOperator> fixed_;
  SeparableBandedOperator op_;
  BandedLdlt fi_, fj_;
  ColumnForms forms_;                     // of the B rhs_scaling() read, for the do_solve() that follows
  const double* forms_source_ = nullptr;  // that B's data
};

}  // namespace

SolveStatus banded_ldlt(const std::array<double, 3>& a, int k, BandedLdlt& f) {
  f.d.resize(k);
  f.l1.resize(std::max(0, k - 1));
  f.l2.resize(std::max(0, k - 2));
  const double scale = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])});
  for (int r = 0; r < k; ++r) {
    double d = a[0];
    if (r >= 1) d -= f.l1[r - 1] * f.l1[r - 1] * f.d[r - 1];
    if (r >= 2) d -= f.l2[r - 2] * f.l2[r - 2] * f.d[r - 2];
    // Pivots of one sign so far: the leading block is definite, and a zero last pivot makes the
    // factor singular (semidefinite). Any other zero pivot, or a change of sign, says only that
    // the factor is indefinite, where elimination without pivoting is unstable.
    if (!(std::abs(d) > 1e-14 * scale)) return r + 1 == k ? SolveStatus::kSingular : SolveStatus::kNotApplicable;
    if (r >= 1 && (d > 0) != (f.d[0] > 0)) return SolveStatus::kNotApplicable;
    f.d[r] = d;
    if (r + 1 < k) {
      double l = a[1];
      if (r >= 1) l -= f.l2[r - 1] * f.d[r - 1] * f.l1[r - 1];
      f.l1[r] = l / d;
    }
    if (r + 2 < k) f.l2[r] = a[2] / d;
  }
  return SolveStatus::kSuccess;
}

Eigen::SparseMatrix<double> separable_banded_matrix(const SeparableBandedOperator& op) {
  const auto span = [](int k, int len) { return std::min(len - 1, k + 2) - std::max(0, k - 2) + 1; };
  Eigen::Index nnz = 0;
  for (int i = 0; i < op.rows; ++i)
    for (int j = 0; j < op.cols; ++j) nnz += Eigen::Index(span(i, op.rows)) * span(j, op.cols);
  return matrix_by_columns(op.size(), nnz, [&](Eigen::Index k, const auto& emit) {
    const int i = int(k / op.cols), j = int(k % op.cols);
    for (int a = std::max(-2, -i); a <= std::min(2, op.rows - 1 - i); ++a)
      for (int b = std::max(-2, -j); b <= std::min(2, op.cols - 1 - j); ++b)
        emit(Eigen::Index(i + a) * op.cols + j + b,
             op.along_i[std::size_t(std::abs(a))] * op.along_j[std::size_t(std::abs(b))]);
  });
}

SolveStatus separable_banded_solve(const SeparableBandedOperator& op, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X,
                                   int threads) {
  BandedLdlt fi, fj;
  if (B.rows() != op.size()) return SolveStatus::kNotApplicable;
  for (SolveStatus status : {banded_ldlt(op.along_i, op.rows, fi), banded_ldlt(op.along_j, op.cols, fj)})
    if (status != SolveStatus::kSuccess) return status;
  solve_separable(fi, fj, op.rows, op.cols, B, X, threads);
  return SolveStatus::kSuccess;
}

std::unique_ptr<LinearSolver> make_separable_banded_solver(const SeparableBandedOperator& op,
                                                           const SolverOptions& options) {
  return std::make_unique<SeparableBandedSolver>(op, options);
}

std::unique_ptr<LinearSolver> make_separable_banded(const SolverOptions& options) {
  return std::make_unique<SeparableBandedSolver>(std::nullopt, options);
}

std::optional<SeparableBandedOperator> separable_operator(const StencilOperator& g) {
  if (!g.is_valid(nullptr) || g.size() != Eigen::Index(g.rows) * g.cols) return std::nullopt;
  const auto split = rank_one_split(g);
  if (!split) return std::nullopt;
  const int r = g.radius;
  const double tol = 1e-12 * std::abs(g.weight(split->a0, split->b0));  // the pivot is the largest weight
  for (int di = -r; di <= r; ++di)
    for (int dj = -r; dj <= r; ++dj) {
      const double w = g.weight(di, dj);
      if (std::abs(w - g.weight(-di, dj)) > tol || std::abs(w - g.weight(di, -dj)) > tol) return std::nullopt;
    }
  SeparableBandedOperator op;
  op.rows = g.rows;
  op.cols = g.cols;
  for (int k = 0; k <= r; ++k) {
    const std::size_t at = std::size_t(k) + std::size_t(r);  // offset k in the split's vectors
    op.along_i[std::size_t(k)] = split->u[at];
    op.along_j[std::size_t(k)] = split->v[at];
  }
  return op;
}

std::optional<SeparableBandedOperator> separable_operator(const LinearOperator& op) {
  if (op.grid) return separable_operator(*op.grid);
  if (op.stencil) return separable_operator(stencil_operator(*op.stencil));
  return std::nullopt;
}

}  // namespace coons::solvers
