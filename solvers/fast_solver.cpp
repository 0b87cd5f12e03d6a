// fast: the structured solver of structured_solvers.h. Per factorisation it picks one of three
// paths: the Kronecker path (kronecker_solver.h) when c·d = e_i·e_j; otherwise a sine transform
// along j (sine_transform.h) and the batch of tridiagonal solves along i of every mode
// (mode_pivots.h), vectorised across the modes, on a grid widened to a fast transform length
// when needed (capacitance.h); and the dst solver where elimination without pivoting would be
// unsafe. Right-hand sides are read row by row (row_form.h): only full rows are transformed.
// This file holds the orchestration and the pipeline of the transform path, which
// SolverOptions::threads splits by modes (the tridiagonal sweeps) and by rows (the inverse
// transforms) with OpenMP: bit for bit the one-thread result.
// Sizes: #interior by 3 in and out; O(L) work arrays, 3 blocks of K·L for the pipeline.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "capacitance.h"
#include "kronecker_solver.h"
#include "mode_pivots.h"
#include "row_form.h"
#include "row_kernels.h"
#include "sine_transform.h"
#include "structured_solvers.h"

namespace coons::solvers {
namespace {

using detail::AlignedBuffer;
using detail::Capacitance;
using detail::KroneckerSolve;
using detail::ModePivots;
using detail::RowForm;
using detail::SineTransform;

// Largest prime factor of n ≥ 1.
int largest_prime_factor(int n) {
  int largest = 1;
  for (int f = 2; f * f <= n; ++f)
    while (n % f == 0) {
      largest = f;
      n /= f;
    }
  return std::max(largest, n);
}

// Columns to add so that the sine transform has a fast length: FFTW has codelets for the factors
// up to 13, and falls back to an O(p²) one for a larger prime p (a length of 1023 = 3·11·31 is 9×
// slower than 1024). Up to four extra columns, 7-smooth; 0 keeps the length.
int extra_columns(int cols) {
  if (largest_prime_factor(cols + 1) <= 13) return 0;
  for (int k = 1; k <= 4; ++k)
    if (largest_prime_factor(cols + k + 1) <= 7) return k;
  return 0;
}

// ------------------------------------------------------------------------------------------------

class FastSolver : public detail::StructuredSolver {
 public:
  explicit FastSolver(const SolverOptions& options) : StructuredSolver(options) {}
  [[nodiscard]] std::string name() const override { return "fast"; }

 protected:
  // A sweep splits the basis right-hand sides by rows and sine-transforms them once (SweepForms),
  // and combines the forms per member. Its workers (one per thread) share those forms.
  void do_begin_sweep() override { sweep_forms_.reset(); }
  SolveStatus do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::MatrixX3d& X, SolveSummary& summary) override;
  std::unique_ptr<LinearSolver> make_sweep_worker(const std::vector<Eigen::MatrixX3d>& basis,
                                                  const LinearOperator& op) override {
    SolverOptions one = options_;
    one.threads = 1;
    auto worker = std::make_unique<FastSolver>(one);
    if (worker->analyze(op) != SolveStatus::kSuccess) return nullptr;
    if (!worker->fits(sweep_forms_.get(), basis)) sweep_forms_ = worker->make_sweep_forms(basis);
    worker->sweep_forms_ = sweep_forms_;
    return worker;
  }

  SolveStatus analyze_grid(SolveSummary& /*summary*/) override {
    extra_ = extra_columns(C_);
    L_ = C_ + extra_;
    const std::size_t L = std::size_t(L_);
#if defined(_OPENMP)
    threads_ = std::max(1, std::min(resolved_threads(options_.threads), L_ / 64));
#else
    threads_ = 1;
#endif
    sines_.clear();
    rows_.clear();
    for (int t = 0; t < threads_; ++t) {
      sines_.emplace_back(L_, detail::fft_planning(options_));
      rows_.emplace_back(L);
    }
    if (extra_ > 0) capacitance_.prepare(R_, detail::fft_planning(options_));
    auto sine_column = [&](int j, std::vector<double>& v) {  // S·e_j, length L
      v.resize(L);
      for (int q = 0; q < L_; ++q) v[std::size_t(q)] = std::sin(M_PI * double(j + 1) * (q + 1) / (L_ + 1));
    };
    y_.resize(L);
    for (int q = 0; q < L_; ++q) y_[std::size_t(q)] = std::cos(M_PI * (q + 1) / (L_ + 1));
    sine_column(0, sine_e0_);
    if (C_ >= 2)
      sine_column(C_ - 1, sine_e1_);
    else
      sine_e1_.assign(L, 0.0);  // a row of one value has no second end
    sine_extra_.assign(std::size_t(extra_), {});
    for (int m = 0; m < extra_; ++m) sine_column(C_ + m, sine_extra_[std::size_t(m)]);
    unit_e0_.assign(std::size_t(C_), 0.0);
    unit_e1_.assign(std::size_t(C_), 0.0);
    unit_e0_[0] = 1;
    if (C_ >= 2) unit_e1_[std::size_t(C_ - 1)] = 1;
    for (auto& w : running_) w = AlignedBuffer(L);
    for (auto& y : forward_) y = AlignedBuffer();  // made by the first solve that needs them
    // Blocks of the back substitution: 3·K rows of L doubles, to stay in the L2 cache.
    block_rows_ = std::max(2, std::min(R_, std::clamp(16384 / L_, 4, 32)));
    for (auto& b : block_) b = AlignedBuffer(std::size_t(block_rows_) * L);
    dst_.reset();
    return SolveStatus::kSuccess;
  }

  SolveStatus factorize_grid(const LinearOperator& op, const GridStencil& s, SolveSummary& summary) override {
    if (KroneckerSolve::applies(s) && kronecker_.factor(s)) {
      path_ = Path::kKronecker;
      return SolveStatus::kSuccess;
    }
    if (modes_.factor(s, y_) && (extra_ == 0 || capacitance_.factor(s, y_, sine_extra_))) {
      path_ = Path::kTransform;
      return SolveStatus::kSuccess;
    }
    // Elimination without pivoting is unsafe for some mode: the 2-D transform has no pivots.
    path_ = Path::kDst;
    if (!dst_) {
      SolverOptions inner = options_;
      inner.compute_residual = false;
      dst_ = make_dst_solver(inner);
    }
    const SolveStatus status = dst_->factorize(op);
    if (status != SolveStatus::kSuccess) summary.message = dst_->summary().message;
    return status;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    summary.iterations = 1;
    if (path_ == Path::kDst) {
      const SolveSummary inner = dst_->solve(B, X);
      summary.message = inner.message;
      return inner.status;
    }
    X.resize(B.rows(), 3);
    std::array<RowForm, 3> forms;
    // (Serial: a parallel region of its own would cost a second wait for a descheduled thread on
    // a busy machine, more than the scan itself.)
    for (int c = 0; c < 3; ++c) forms[std::size_t(c)] = detail::split_rows(B.col(c).data(), R_, C_);
    if (path_ == Path::kKronecker) {
      for (int c = 0; c < 3; ++c) kronecker_.solve(forms[std::size_t(c)], B.col(c).data(), X.col(c).data());
    } else {
      for (auto& f : forms) transform_rows(f);
      solve_transform(forms, X);
    }
    return SolveStatus::kSuccess;
  }

 private:
  enum class Path { kKronecker, kTransform, kDst };
  // Dense rows of a form → their sine transforms of length L (zero-padded).
  void transform_rows(RowForm& f) {
    const std::size_t C = std::size_t(f.width), L = std::size_t(L_);
    if (f.width == L_) {
      for (std::size_t k = 0; k < f.dense_rows.size(); ++k) {
        double* row = f.values.data() + k * L;
        sines_[0].apply(row, row, 1.0);
      }
      return;
    }
    std::vector<double> values(f.dense_rows.size() * L, 0.0);
    for (std::size_t k = 0; k < f.dense_rows.size(); ++k) {
      double* row = values.data() + k * L;
      std::copy(f.values.data() + k * C, f.values.data() + (k + 1) * C, row);
      sines_[0].apply(row, row, 1.0);
    }
    f.values = std::move(values);
    f.width = L_;
  }

  // For every mode q: X̂(:,q) = T_q⁻¹ (B̂(:,q) + sources on the extra columns), three columns at
  // once, each X̂ row handed to finish(t, i, c, x̂) (t: the calling thread). Every loop runs over
  // whole rows, vectorised across the modes. The forward elimination keeps only the last row of
  // each block of K rows (in rows[c] + i·stride: X itself when L = C) and recomputes a block in
  // cache before substituting back through it: two passes over memory fewer for a little more
  // arithmetic. One thread hands each row to finish as soon as its block is done (so that the
  // inverse transform runs while the row is in cache). Several threads take a chunk of modes each
  // (dynamically: a thread that starts late on a busy machine may find none left), write x̂ to
  // rows, and after one barrier finish the rows, again dynamically. (More, smaller chunks were
  // slower: every row step has a fixed cost. The pass of x̂ through rows, a write and a read of the
  // grid more than one thread does, is why two threads gain little over one.)
  // Every chunk and row is computed alike whoever takes it: bit for bit the one-thread result.
  template <class Finish>
  void pipeline(const std::array<RowForm, 3>& forms, const std::array<const double*, 3>& sources,
                const std::array<double*, 3>& rows, std::size_t stride, Finish&& finish) {
    const int T = threads_;
    if (T == 1) {
      solve_modes(forms, sources, rows, stride, 0, L_, [&](int i, int c, const double* xh) { finish(0, i, c, xh); });
      detail::stream_fence();  // the non-temporal stores of finish, as on the threaded path
      return;
    }
    const int chunks = std::max(1, std::min(T, L_ / 64));
    auto chunk_start = [&](int k) { return k == chunks ? L_ : int(long(k) * L_ / chunks) / 8 * 8; };
#if defined(_OPENMP)
#pragma omp parallel num_threads(T)
#endif
    {
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 1)
#endif
      for (int k = 0; k < chunks; ++k) {
        const int q0 = chunk_start(k), q1 = chunk_start(k + 1);
        solve_modes(forms, sources, rows, stride, q0, q1 - q0, [&](int i, int c, const double* xh) {
          std::copy(xh, xh + (q1 - q0), rows[std::size_t(c)] + std::size_t(i) * stride + std::size_t(q0));
        });
      }  // (the implied barrier: every mode of x̂ is in rows)
      const int t = thread_index();
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 16)
#endif
      for (int k = 0; k < 3 * R_; ++k) {
        const int i = k / 3, c = k % 3;
        finish(t, i, c, static_cast<const double*>(rows[std::size_t(c)] + std::size_t(i) * stride));
      }
      detail::stream_fence();
    }
  }

  // The modes [q0, q0 + n) of every row: forward elimination and back substitution, handing each
  // row of x̂ (those modes, from q0) to done(i, c, x̂) when its block is substituted. Only the
  // modes [q0, q0 + n) of the pivots, the blocks, running_ and the saved rows are touched.
  template <class Done>
  void solve_modes(const std::array<RowForm, 3>& forms, const std::array<const double*, 3>& sources,
                   const std::array<double*, 3>& rows, std::size_t stride, int q0, int n, Done&& done) {
    const std::size_t L = std::size_t(L_);
    const int K = block_rows_;
    const int last_block = (R_ - 1) / K;
    const double* o = modes_.off() + q0;
    const double* l = modes_.multipliers() + q0;
    const double* r = modes_.pivots() + q0;
    auto saved = [&](int c, int i) { return rows[std::size_t(c)] + std::size_t(i) * stride + std::size_t(q0); };
    auto slot_row = [&](int c, int s) { return block_[std::size_t(c)].data() + std::size_t(s) * L + std::size_t(q0); };
    int at = -1;  // the row held by the running pivot row (in these modes)
    auto pivots_for = [&](int i) {
      if (at != i) modes_.load(at, i, q0, q0 + n);
      at = i;
    };
    // Row i of the forward elimination: y_i = B̂_i − l_i ∘ y_{i−1}, l_i = o ∘ r_{i−1}.
    auto eliminate = [&](int i, int c, const double* p, double* y) {
      const RowForm& f = forms[std::size_t(c)];
      const int slot = f.slot[std::size_t(i)];
      if (slot >= 0)
        detail::eliminate_dense(f.values.data() + std::size_t(slot) * L + std::size_t(q0), l, p, y, n);
      else
        detail::eliminate_sparse(f.first[std::size_t(i)], f.last[std::size_t(i)], sine_e0_.data() + q0,
                                 sine_e1_.data() + q0, l, p, y, n);
      if (const double* u = sources[std::size_t(c)])
        for (int m = 0; m < extra_; ++m)
          detail::add_scaled(u[std::size_t(i) * std::size_t(extra_) + std::size_t(m)],
                             sine_extra_[std::size_t(m)].data() + q0, y, n);
    };
    // Row i of all three columns: one pass over s, t and l when every column's row is sparse
    // and there are no sources (rows of mask data but two), else column by column.
    auto eliminate3 = [&](int i, auto&& previous, auto&& target) {
      const std::size_t k = std::size_t(i);
      if (extra_ == 0 && forms[0].slot[k] < 0 && forms[1].slot[k] < 0 && forms[2].slot[k] < 0) {
        const std::array<double, 3> a{forms[0].first[k], forms[1].first[k], forms[2].first[k]};
        const std::array<double, 3> e{forms[0].last[k], forms[1].last[k], forms[2].last[k]};
        const std::array<double*, 3> x{target(0), target(1), target(2)};
        const std::array<const double*, 3> p{previous(0), previous(1), previous(2)};
        detail::eliminate_sparse3(a.data(), e.data(), sine_e0_.data() + q0, sine_e1_.data() + q0, l,
                                  i > 0 ? p.data() : nullptr, x.data(), n);
        return;
      }
      for (int c = 0; c < 3; ++c) eliminate(i, c, previous(c), target(c));
    };
    for (int i = 0; i < R_; ++i) {
      if (i > 0) pivots_for(i - 1);
      const int s = i % K;
      eliminate3(
          i, [&](int c) { return i > 0 ? slot_row(c, (s + K - 1) % K) : nullptr; },
          [&](int c) { return slot_row(c, s); });
      if (s == K - 1 && i + 1 < R_)
        for (int c = 0; c < 3; ++c) std::copy(slot_row(c, s), slot_row(c, s) + n, saved(c, i));
    }
    // Back substitution, x̂_i = (y_i − o ∘ x̂_{i+1}) ∘ r_i in place of y_i, block by block from the
    // last one (whose rows are still in the buffer); running_ holds x̂ of the block below.
    for (auto& w : running_) std::fill(w.data() + q0, w.data() + q0 + n, 0.0);
    for (int b = last_block; b >= 0; --b) {
      const int first = b * K, end = std::min(R_, first + K);
      if (b != last_block)
        for (int i = first; i < end; ++i) {
          if (i > 0) pivots_for(i - 1);
          eliminate3(
              i,
              [&](int c) -> const double* {
                return i == 0 ? nullptr : i == first ? saved(c, i - 1) : slot_row(c, i - first - 1);
              },
              [&](int c) { return slot_row(c, i - first); });
        }
      for (int i = end - 1; i >= first; --i) {
        pivots_for(i);
        std::array<double*, 3> y{};
        std::array<const double*, 3> next{};
        for (int c = 0; c < 3; ++c) {
          y[std::size_t(c)] = slot_row(c, i - first);
          next[std::size_t(c)] = i + 1 < end ? slot_row(c, i + 1 - first) : running_[std::size_t(c)].data() + q0;
        }
        detail::back_substitute_in_place3(y.data(), o, r, next.data(), n);
      }
      for (int c = 0; c < 3; ++c) std::copy(slot_row(c, 0), slot_row(c, 0) + n, running_[std::size_t(c)].data() + q0);
      for (int i = end - 1; i >= first; --i)
        for (int c = 0; c < 3; ++c) done(i, c, static_cast<const double*>(slot_row(c, i - first)));
    }
  }

  // X = (2/(L+1)) S X̂, first C columns; with extra columns, the sources U are found first from a
  // pipeline that only records the solution on the extra columns.
  void solve_transform(const std::array<RowForm, 3>& forms, Eigen::MatrixX3d& X) {
    const std::size_t C = std::size_t(C_);
    const double scale = 2.0 / (L_ + 1);
    std::array<const double*, 3> sources{nullptr, nullptr, nullptr};
    std::array<std::vector<double>, 3> U;
    // The forward rows: in X itself when they fit, else in buffers of the widened grid.
    std::array<double*, 3> rows{X.col(0).data(), X.col(1).data(), X.col(2).data()};
    std::size_t stride = C;
    if (extra_ > 0) {
      stride = forward_stride();
      for (int c = 0; c < 3; ++c) {
        AlignedBuffer& y = forward_[std::size_t(c)];
        if (y.size() != std::size_t(R_) * stride) y = AlignedBuffer(std::size_t(R_) * stride);
        rows[std::size_t(c)] = y.data();
      }
    }
    if (extra_ > 0) {
      const std::size_t k = std::size_t(extra_), R = std::size_t(R_);
      std::array<std::vector<double>, 3> V;
      for (auto& v : V) v.assign(R * k, 0.0);
      pipeline(forms, sources, rows, stride, [&](int /*t*/, int i, int c, const double* xh) {
        for (std::size_t m = 0; m < k; ++m)
          V[std::size_t(c)][std::size_t(i) * k + m] = scale * detail::dot(sine_extra_[m].data(), xh, L_);
      });
      for (int c = 0; c < 3; ++c) {
        capacitance_.sources(V[std::size_t(c)], U[std::size_t(c)]);
        sources[std::size_t(c)] = U[std::size_t(c)].data();
      }
    }
    pipeline(forms, sources, rows, stride, [&](int t, int i, int c, const double* xh) {
      double* row = rows_[std::size_t(t)].data();
      sines_[std::size_t(t)].apply(xh, row, scale);
      detail::stream_copy(row, X.col(c).data() + std::size_t(i) * C, C);
    });
  }

  int L_ = 0, extra_ = 0, block_rows_ = 16;
  Path path_ = Path::kTransform;
  // The threads of a solve (SolverOptions::threads, at most one per 64 modes); they take chunks
  // of modes whose bounds are multiples of 8 (whole cache lines).
  int threads_ = 1;
  std::vector<SineTransform> sines_;  // one per thread (a transform has scratch)
  std::vector<AlignedBuffer> rows_;   // one row of L per thread
  std::vector<double> y_, sine_e0_, sine_e1_, unit_e0_, unit_e1_;
  std::vector<std::vector<double>> sine_extra_;
  ModePivots modes_;          // the transform path's tridiagonal systems, one per mode
  Capacitance capacitance_;   // the widened grid's sources
  KroneckerSolve kronecker_;  // the Kronecker path
  std::array<AlignedBuffer, 3> running_, forward_, block_;
  // Rows of forward_ (used when L > C) start at multiples of 64 bytes.
  [[nodiscard]] std::size_t forward_stride() const { return (std::size_t(L_) + 7) / 8 * 8; }
  std::unique_ptr<LinearSolver> dst_;

  // Every right-hand side of a sweep's basis split by rows (physical: the Kronecker path) and with
  // its dense rows sine-transformed (transformed: the transform path), for an R × C grid.
  struct SweepForms {
    int rows = 0, cols = 0;
    std::vector<std::array<RowForm, 3>> physical, transformed;
  };
  [[nodiscard]] bool fits(const SweepForms* forms, const std::vector<Eigen::MatrixX3d>& basis) const {
    return forms && forms->rows == R_ && forms->cols == C_ && forms->physical.size() == basis.size();
  }
  std::shared_ptr<const SweepForms> make_sweep_forms(const std::vector<Eigen::MatrixX3d>& basis) {
    auto forms = std::make_shared<SweepForms>();
    forms->rows = R_;
    forms->cols = C_;
    forms->physical.resize(basis.size());
    for (std::size_t r = 0; r < basis.size(); ++r)
      for (int c = 0; c < 3; ++c)
        forms->physical[r][std::size_t(c)] = detail::split_rows(basis[r].col(c).data(), R_, C_);
    forms->transformed = forms->physical;
    for (auto& f : forms->transformed)
      for (RowForm& column : f) transform_rows(column);
    return forms;
  }
  std::shared_ptr<const SweepForms> sweep_forms_;  // read-only once made: a sweep's workers share it
};

SolveStatus FastSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& w,
                                       Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::Index n = Eigen::Index(R_) * C_;
  const std::size_t used = w.size();
  summary.iterations = 1;
  X.resize(n, 3);
  if (path_ == Path::kDst) {
    const SolveSummary inner = dst_->solve(combine_rhs(basis, w, n), X);
    summary.message = inner.message;
    return inner.status;
  }
  if (!fits(sweep_forms_.get(), basis)) sweep_forms_ = make_sweep_forms(basis);
  const bool kron = path_ == Path::kKronecker;
  const auto& forms_of_basis = kron ? sweep_forms_->physical : sweep_forms_->transformed;
  std::array<RowForm, 3> forms;
  for (int c = 0; c < 3; ++c) {
    std::vector<const RowForm*> parts;
    for (std::size_t r = 0; r < used; ++r) parts.push_back(&forms_of_basis[r][std::size_t(c)]);
    forms[std::size_t(c)] =
        kron ? detail::combine(parts, w, R_, unit_e0_, unit_e1_) : detail::combine(parts, w, R_, sine_e0_, sine_e1_);
  }
  if (!kron) {
    solve_transform(forms, X);
    return SolveStatus::kSuccess;
  }
  Eigen::MatrixX3d B;  // formed only for a column with too many full rows for the rank form
  for (int c = 0; c < 3; ++c) {
    if (int(forms[std::size_t(c)].dense_rows.size()) > KroneckerSolve::kMaxRank && B.rows() == 0)
      B = combine_rhs(basis, w, n);
    kronecker_.solve(forms[std::size_t(c)], B.col(c).data(), X.col(c).data());
  }
  return SolveStatus::kSuccess;
}

}  // namespace

std::unique_ptr<LinearSolver> make_fast_solver(const SolverOptions& options) {
  return std::make_unique<FastSolver>(options);
}

}  // namespace coons::solvers
